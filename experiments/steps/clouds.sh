# Steps dataset and dense: the Blender line clouds of the Roof-Image buildings (sourced by experiments/run.sh).

# All 3,583 buildings from 20 views -> runs/dataset. Train + validation first, so that `train` can start (or
# resume after a lost machine) before the test clouds exist; summary.json describes the training clouds (the
# model card quotes it).
step_dataset() {
  LC2WF_WITH_RENDER_TOOLS=1 "$root/tools/setup-deps.sh"
  link_meshes runs/trainval-meshes configs/splits/train.txt configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/trainval-meshes --out runs/dataset --renderer blender -j 2 \
    > runs/dataset-summary-trainval.json
  link_meshes runs/test-meshes configs/splits/test.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/test-meshes --out runs/dataset --renderer blender -j 2 \
    > runs/dataset-summary-test.json
  cp runs/dataset-summary-trainval.json runs/dataset/summary.json.tmp && mv runs/dataset/summary.json.tmp runs/dataset/summary.json
  cp runs/dataset-summary-test.json runs/dataset/summary-test.json
}

# The Roof-Image test split's 30-view Blender clouds (the paper's benchmark as the README scores it) ->
# runs/dataset-30v, resumable; also used by general-eval.
dense_test_clouds() {
  LC2WF_WITH_RENDER_TOOLS=1 "$root/tools/setup-deps.sh"
  link_meshes runs/test-meshes configs/splits/test.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/test-meshes --out runs/dataset-30v --renderer blender --views 30 -j 2 \
    > runs/dataset-30v-summary-test.json
}

# More views give the junction model the walls' feet it misses (experiments/README.md, "Denser clouds"): the
# same renders from 30 views -> runs/dataset-30v. The test split first, so the shipped models can be scored on
# it while the validation and training clouds are made.
step_dense() {
  dense_test_clouds
  # The validation split next (200 buildings): test-time options are chosen on it while the training
  # clouds are made; the train + val pass below skips its finished buildings.
  link_meshes runs/val-meshes configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/val-meshes --out runs/dataset-30v --renderer blender --views 30 \
    -j 2 > runs/dataset-30v-summary-val.json
  link_meshes runs/trainval-meshes configs/splits/train.txt configs/splits/val.txt
  "$build_dir/tools/lc2wf-dataset" "${fixed_size[@]}" --meshes runs/trainval-meshes --out runs/dataset-30v --renderer blender --views 30 \
    -j 2 > runs/dataset-30v-summary-trainval.json
  cp runs/dataset-30v-summary-trainval.json runs/dataset-30v/summary.json.tmp
  mv runs/dataset-30v/summary.json.tmp runs/dataset-30v/summary.json
  cp runs/dataset-30v-summary-test.json runs/dataset-30v/summary-test.json
}
