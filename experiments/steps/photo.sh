# Step photo-data: photo-like clouds for the next training round. The photo benchmark (bench/README.md,
# "reconstruct") showed the model, not the poses or the scale, failing on photos: with GPS the scale is right to
# 1 %, yet the known-camera photo-like clouds score 9 sAP and the wireframes are 2-3 times the GT's length
# (window frames, trees, neighbours taken for edges). The mixes so far held 153 photo-like clouds (5 %), all at
# 640 x 480, and no photo-like validation cloud. Blender, --textures photo, 30 views, lc2wf-dataset's default
# pixel rule: every 4th real training building of general2's mix not yet rendered photo-like, every 4th
# generated training building likewise, and every 7th real validation building as a photo-like validation
# set -> runs/photo/{real,gen,realval}-blender (resumable; needs general-data's and general2-data's lists).
step_photo_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  [[ -s runs/general2/photo-names.txt ]] || die 3 "no general2 mix: run experiments/run.sh general2-data first"
  mkdir -p runs/photo/meshes-gen
  [[ -f runs/photo/real-names.txt ]] ||
    sort runs/general/real-train-sub.txt runs/general2/real-train-add.txt | sed 's/^/photo_/' |
    comm -23 - <(sort runs/general/photo-names.txt runs/general2/photo-names.txt) | awk 'NR % 4 == 1' > runs/photo/real-names.txt
  [[ -f runs/photo/realval-names.txt ]] ||
    awk 'NR % 7 == 1 { print "photo_" $0 }' runs/general2/realval-names.txt > runs/photo/realval-names.txt
  local g
  # general-data rendered every 10th generated building (NR % 10 == 1) photo-like; these are others.
  for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 4 == 2'); do
    ln -sfn "$(realpath "$g")" "runs/photo/meshes-gen/photo_$(basename "$g")"
  done
  local common=(--renderer blender --textures photo --views 30 -j 2 -q)
  "$dataset" --meshes runs/general/lod2-photo --names runs/photo/realval-names.txt --out runs/photo/realval-blender "${common[@]}" \
    > runs/photo/realval.json || true
  "$dataset" --meshes runs/general/lod2-photo --names runs/photo/real-names.txt --out runs/photo/real-blender "${common[@]}" \
    > runs/photo/real.json || true
  "$dataset" --meshes runs/photo/meshes-gen --out runs/photo/gen-blender "${common[@]}" > runs/photo/gen.json || true
  echo "photo-data: $(ls runs/photo/real-blender/clouds | wc -l) real and $(ls runs/photo/gen-blender/clouds | wc -l) generated" \
    "training clouds, $(ls runs/photo/realval-blender/clouds | wc -l) validation clouds in runs/photo"
}
