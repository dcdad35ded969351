# The fifth round: photo clutter in training. models/general scores 9.6 / 5.5 sAP on photo-like clouds of real
# validation buildings against 49.0 / 33.0 on raster clouds of the same buildings (experiments/README.md, "The
# fifth round"): its mixes held 5 % photo-like clouds, at 640 x 480. photo5-data: a fine-tuning mix of every
# photo-like training cloud photo-data has made (runs/photo/{real,gen}-blender) and every 3rd cloud of general4's
# mix (raster and Blender, so the clean clouds stay in the distribution); validation: the 60 photo-like
# validation clouds and every 3rd of general4's validation clouds. The lists are written once (a resumed training
# keeps its data) and the photo part is kept in experiments/lists/photo5-photo.txt, so a fresh machine trains on
# the same clouds once photo-data has rendered them.
# photo5_link CLOUDS NAMES: CLOUDS/<name>.lcloud of every name in the file NAMES linked into runs/photo5/clouds.
photo5_link() {
  local name
  while read -r name; do ln -sfn "$(realpath "$1/$name.lcloud")" runs/photo5/clouds/; done < "$2"
}

# photo5_split SPLIT PHOTO_NAMES: runs/photo5/SPLIT.txt = the photo-like names (already linked) and every 3rd
# cloud of general4's SPLIT list.
photo5_split() {
  awk 'NR % 3 == 1' "runs/general4/$1.txt" > "runs/photo5/clean-$1.txt"
  photo5_link runs/general4/clouds "runs/photo5/clean-$1.txt"
  sort -u "$2" "runs/photo5/clean-$1.txt" > "runs/photo5/$1.txt"
}

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
    photo5_split train experiments/lists/photo5-photo.txt
  fi
  if [[ ! -s runs/photo5/val.txt ]]; then
    photo5_link runs/photo/realval-blender/clouds experiments/lists/photo-realval.txt
    photo5_split val experiments/lists/photo-realval.txt
  fi
  echo "photo5-data: $(wc -l < runs/photo5/train.txt) training clouds ($(wc -l < experiments/lists/photo5-photo.txt)" \
    "photo-like), $(wc -l < runs/photo5/val.txt) validation clouds in runs/photo5"
}

# photo5-train [FLAGS...]: experiments/configs/photo5.json (models/general fine-tuned on the mix), resumable.
step_photo5_train() { train_mix photo5 photo5-model experiments/configs/photo5.json "$@"; }
