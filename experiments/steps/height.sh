# Step height-model: the height model of models/general (dataset/photo/line_height.h), which scales photo
# clouds and line maps nothing else scales. Its training clouds are the light2 mix's metric clouds of real and
# generated training buildings, clean and photo-look, plus the other half of the photo-look real training
# buildings and 40 more generated ones in the photo look (≈ 25 min of raster renders on two cores); then
# lc2wf-fit-height (a second) -> runs/height/height.json, copied to models/general/height.json by hand
# after validation (experiments/README.md, "Height from line statistics").

step_height_model() {
  need_binary "$build_dir/tools/lc2wf-dataset" lc2wf-dataset
  need_binary "$build_dir/train/lc2wf-fit-height" lc2wf-fit-height
  [[ -d runs/light2/realphoto && -d runs/light2/real && -d runs/light2/gen && -d runs/light2/genphoto ]] || step_light2_data
  mkdir -p runs/height runs/height/meshes-genphoto2
  local g
  for g in $(ls runs/general/meshes-gen/*.polyshape | awk 'NR % 15 == 10'); do
    ln -sfn "$(realpath "$g")" "runs/height/meshes-genphoto2/photo_$(basename "$g")"
  done
  [[ -s runs/height/realphoto2-names.txt ]] || awk 'NR % 2 == 0' experiments/lists/photo-real.txt > runs/height/realphoto2-names.txt
  mesh_names runs/height/meshes-genphoto2 runs/height/genphoto2-names.txt
  render_part height runs/general/lod2-photo realphoto2 --names runs/height/realphoto2-names.txt --textures photo
  render_part height runs/height/meshes-genphoto2 genphoto2 --names runs/height/genphoto2-names.txt --textures photo
  # k = 5: on the 83 photo-look validation clouds 10.8 % median error against 13.0 % with the 3 the
  # cross-validation picked (experiments/README.md, "Height from line statistics").
  "$build_dir/train/lc2wf-fit-height" -o runs/height/height.json --ks 5 runs/light2/{realphoto,genphoto,real,gen}/clouds \
    runs/height/{realphoto2,genphoto2}/clouds
}
