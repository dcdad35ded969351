# Step photo-data: photo-like clouds for the next training round. The photo benchmark (bench/README.md,
# "reconstruct") showed the model, not the poses or the scale, failing on photos: with GPS the scale is right to
# 1 %, yet the known-camera photo-like clouds score 9 sAP and the wireframes are 2-3 times the GT's length
# (window frames, trees, neighbours taken for edges). The mixes so far held 153 photo-like clouds (5 %), all at
# 640 x 480, and no photo-like validation cloud. Blender, --textures photo, 30 views, lc2wf-dataset's default
# pixel rule -> runs/photo/{realval,real,gen}-blender (resumable: finished buildings are skipped).
# The real buildings are the committed lists experiments/lists/photo-real.txt (every 4th real training building
# of general2's mix not yet rendered photo-like) and photo-realval.txt (every 7th real validation building), so
# a fresh machine needs only general_meshes (seconds), not the earlier mixes' renders; the generated ones are
# every 4th of general's seeded meshes (general-data took every 10th: NR % 10 == 1, never NR % 4 == 2).
step_photo_data() {
  local dataset=$build_dir/tools/lc2wf-dataset
  need_binary "$dataset" lc2wf-dataset
  [[ -f runs/general/meshes-gen/buildings.json && -d runs/lod2-all ]] || general_meshes
  photo_lod2_links
  mkdir -p runs/photo/meshes-gen
  local g
  for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 4 == 2'); do
    ln -sfn "$(realpath "$g")" "runs/photo/meshes-gen/photo_$(basename "$g")"
  done
  local common=(--renderer blender --textures photo --views 30 -j 2 -q)
  "$dataset" --meshes runs/general/lod2-photo --names experiments/lists/photo-realval.txt --out runs/photo/realval-blender \
    "${common[@]}" > runs/photo/realval.json || true
  "$dataset" --meshes runs/general/lod2-photo --names experiments/lists/photo-real.txt --out runs/photo/real-blender \
    "${common[@]}" > runs/photo/real.json || true
  "$dataset" --meshes runs/photo/meshes-gen --out runs/photo/gen-blender "${common[@]}" > runs/photo/gen.json || true
  echo "photo-data: $(ls runs/photo/real-blender/clouds | wc -l) real and $(ls runs/photo/gen-blender/clouds | wc -l) generated" \
    "training clouds, $(ls runs/photo/realval-blender/clouds | wc -l) validation clouds in runs/photo"
}
