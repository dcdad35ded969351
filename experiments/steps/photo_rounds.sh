# Fine-tuning rounds with photo clutter in training. models/general scores 9.6 / 5.5 sAP on photo-like clouds of
# real validation buildings against 49.0 / 33.0 on raster clouds of the same buildings (experiments/README.md, "The
# fifth round"): its mixes held 5 % photo-like clouds, at 640 x 480. A round's data step links every photo-like
# training cloud photo-data has made (runs/photo/{real,gen}-blender) and every Nth cloud of general4's mix
# (raster and Blender, so the clean clouds stay in the distribution); validation: the 60 photo-like validation
# clouds and every 3rd of general4's validation clouds (the same in every round, so rounds compare). The lists
# are written once (a resumed training keeps its data) and the photo part is kept in
# experiments/lists/ROUND-photo.txt, so a fresh machine trains on the same clouds once photo-data has made them.
#   photo5: every 3rd clean cloud, the 272 real photo-like clouds rendered when it started, sampled by the old
#           seed order (not shipped).
#   photo6: every 4th clean cloud (a larger photo share), every photo-like cloud at its start, the seed order by
#           endpoint count in its patches and hand-off.

# photo_link ROUND CLOUDS NAMES: CLOUDS/<name>.lcloud of every name in the file NAMES linked into runs/ROUND/clouds.
photo_link() {
  local name
  while read -r name; do ln -sfn "$(realpath "$2/$name.lcloud")" "runs/$1/clouds/"; done < "$3"
}

# photo_split ROUND SPLIT PHOTO_NAMES EVERY: runs/ROUND/SPLIT.txt = the photo-like names (already linked) and every
# EVERY-th cloud of general4's SPLIT list.
photo_split() {
  awk -v every="$4" 'NR % every == 1' "runs/general4/$2.txt" > "runs/$1/clean-$2.txt"
  photo_link "$1" runs/general4/clouds "runs/$1/clean-$2.txt"
  sort -u "$3" "runs/$1/clean-$2.txt" > "runs/$1/$2.txt"
}

# photo_round_data ROUND EVERY: the round's mix in runs/ROUND.
photo_round_data() {
  local round=$1 every=$2 part name
  local photo=experiments/lists/$round-photo.txt
  [[ -s runs/general4/train.txt && -s runs/general4/val.txt ]] || die 3 "no general4 mix: run experiments/run.sh general4-data first"
  mkdir -p "runs/$round/clouds"
  if [[ ! -s $photo ]]; then
    for part in runs/photo/real-blender runs/photo/gen-blender; do
      if [[ -d $part/clouds ]]; then ls "$part/clouds" | sed -n 's/\.lcloud$//p'; fi
    done | sort > "$photo"
  fi
  if [[ ! -s runs/$round/train.txt ]]; then
    while read -r name; do
      for part in runs/photo/real-blender runs/photo/gen-blender; do
        if [[ -f $part/clouds/$name.lcloud ]]; then ln -sfn "$(realpath "$part/clouds/$name.lcloud")" "runs/$round/clouds/"; fi
      done
      [[ -e runs/$round/clouds/$name.lcloud ]] || die 3 "photo-like cloud $name not rendered yet: run experiments/run.sh photo-data"
    done < "$photo"
    photo_split "$round" train "$photo" "$every"
  fi
  if [[ ! -s runs/$round/val.txt ]]; then
    photo_link "$round" runs/photo/realval-blender/clouds experiments/lists/photo-realval.txt
    photo_split "$round" val experiments/lists/photo-realval.txt 3
  fi
  echo "$round-data: $(wc -l < "runs/$round/train.txt") training clouds ($(wc -l < "$photo")" \
    "photo-like), $(wc -l < "runs/$round/val.txt") validation clouds in runs/$round"
}

step_photo5_data() { photo_round_data photo5 3; }
# photo5-train [FLAGS...]: experiments/configs/photo5.json (models/general fine-tuned on the mix), resumable.
step_photo5_train() { train_mix photo5 photo5-model experiments/configs/photo5.json "$@"; }

step_photo6_data() { photo_round_data photo6 4; }
# photo6-train [FLAGS...]: experiments/configs/photo6.json (photo5's schedule on photo6's mix), resumable.
step_photo6_train() { train_mix photo6 photo6-model experiments/configs/photo6.json "$@"; }
