# The fifth round: photo clutter in training. models/general scores 9.6 / 5.5 sAP on photo-like clouds of real
# validation buildings against 49.0 / 33.0 on raster clouds of the same buildings (experiments/README.md, "The
# fifth round"): its mixes held 5 % photo-like clouds, at 640 x 480. photo5-data: a fine-tuning mix of every
# photo-like training cloud photo-data has made (runs/photo/{real,gen}-blender) and every 3rd cloud of general4's
# mix (raster and Blender, so the clean clouds stay in the distribution); validation: the 60 photo-like
# validation clouds and every 3rd of general4's validation clouds. The lists are written once (a resumed training
# keeps its data) and the photo part is kept in experiments/lists/photo5-photo.txt, so a fresh machine trains on
# the same clouds once photo-data has rendered them.
step_photo5_data() {
  [[ -s runs/general4/train.txt && -s runs/general4/val.txt ]] || die 3 "no general4 mix: run experiments/run.sh general4-data first"
  mkdir -p runs/photo5/clouds
  local part name
  if [[ ! -s experiments/lists/photo5-photo.txt ]]; then
    for part in runs/photo/real-blender runs/photo/gen-blender; do
      if [[ -d $part/clouds ]]; then ls "$part/clouds" | sed -n 's/\.lcloud$//p'; fi
    done | sort > experiments/lists/photo5-photo.txt
  fi
  if [[ ! -s runs/photo5/train.txt ]]; then
    while read -r name; do
      for part in runs/photo/real-blender runs/photo/gen-blender; do
        if [[ -f $part/clouds/$name.lcloud ]]; then ln -sfn "$(realpath "$part/clouds/$name.lcloud")" runs/photo5/clouds/; fi
      done
      [[ -e runs/photo5/clouds/$name.lcloud ]] || die 3 "photo-like cloud $name not rendered yet: run experiments/run.sh photo-data"
    done < experiments/lists/photo5-photo.txt
    awk 'NR % 3 == 1' runs/general4/train.txt > runs/photo5/clean-train.txt
    while read -r name; do ln -sfn "$(realpath "runs/general4/clouds/$name.lcloud")" runs/photo5/clouds/; done \
      < runs/photo5/clean-train.txt
    sort -u experiments/lists/photo5-photo.txt runs/photo5/clean-train.txt > runs/photo5/train.txt
  fi
  if [[ ! -s runs/photo5/val.txt ]]; then
    for name in $(cat experiments/lists/photo-realval.txt); do
      ln -sfn "$(realpath "runs/photo/realval-blender/clouds/$name.lcloud")" runs/photo5/clouds/
    done
    awk 'NR % 3 == 1' runs/general4/val.txt > runs/photo5/clean-val.txt
    while read -r name; do ln -sfn "$(realpath "runs/general4/clouds/$name.lcloud")" runs/photo5/clouds/; done \
      < runs/photo5/clean-val.txt
    sort -u experiments/lists/photo-realval.txt runs/photo5/clean-val.txt > runs/photo5/val.txt
  fi
  echo "photo5-data: $(wc -l < runs/photo5/train.txt) training clouds ($(wc -l < experiments/lists/photo5-photo.txt)" \
    "photo-like), $(wc -l < runs/photo5/val.txt) validation clouds in runs/photo5"
}

# photo5-train [FLAGS...]: experiments/configs/photo5.json (models/general fine-tuned on the mix), resumable.
step_photo5_train() { train_mix photo5 photo5-model experiments/configs/photo5.json "$@"; }
