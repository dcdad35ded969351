# Sourced by experiments/run.sh (never run): where the repository, the binaries and the meshes are, and the
# helpers that more than one step uses. Paths in the steps are relative to the repository's root.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${LC2WF_BUILD_DIR:-$root/build}
meshes=${LC2WF_DATA_DIR:-$root/../shared/data}/roof-image/res_building
# lc2wf-dataset as it rendered before large buildings got finer images (640 x 480 for every building): the
# clouds of the paper's run and of the models trained so far, reproduced as they were.
fixed_size=(--max-metres-per-pixel 0)
# The rasteriser as it shaded before the ambient light followed the camera (constant ambient): every raster
# cloud of the models trained so far and of the test scores published with them.
constant_ambient=(--view-light 0)

# die CODE MESSAGE: the step's error on stderr, then exit with CODE (2 bad command line, 3 data or I/O).
die() {
  local code=$1
  shift
  echo "experiments/run.sh: $*" >&2
  exit "$code"
}

# need_binary PATH TARGET: a step's program is built, or the error names the target to build.
need_binary() {
  [[ -x $1 ]] || die 3 "$1 is missing: cmake --build $build_dir --target $2"
}

# The folders of models/ that left the tree in 356e3bf, with the last commit that holds each
# (experiments/README.md, "Models kept only in the history").
declare -A removed_models=(
  [base-training]=e38a11e1422c2ad3bf0e51886d684c834e138326
  [local-labels-training]=e38a11e1422c2ad3bf0e51886d684c834e138326
  [robust-training]=0c3043b5f7a142b138133341d32337dc0d55c3e5
  [junction-turns-training]=72f71643dd2ec0c175263a87d13738348907b078
  [rotate]=7ba152929e866ddbbf483bdda109f24b5e6fb57c
  [rotate-loose]=190bd38e8b0aa537e41a22127f1bfa0018f0d53a
  [edge-sound]=3d40e9a0f95ec2c5f39be71bdbc9e461e05443cc
)

# restore_model NAME: models/NAME back from the git history when it is missing (a step's init weights or
# training state); the restored folder is untracked, not to be committed again.
restore_model() {
  local name=$1
  [[ -d models/$name ]] && return 0
  local commit=${removed_models[$name]:-}
  [[ -n $commit ]] || die 3 "models/$name is missing and is not one of the folders kept in the git history"
  local tmp=models/$name.restore-tmp
  rm -rf "$tmp" && mkdir -p "$tmp"
  echo "experiments/run.sh: restoring models/$name from commit ${commit:0:7}:" \
    "git -C $root archive $commit models/$name | tar -x -C $tmp" >&2
  git -C "$root" archive "$commit" "models/$name" | tar -x -C "$tmp" ||
    die 3 "cannot restore models/$name from commit $commit (a git clone with its history is needed)"
  mv "$tmp/models/$name" "models/$name" && rm -rf "$tmp"
}

# restore_weights WEIGHTS: a weights folder named models/NAME that left the tree is restored first.
restore_weights() {
  local weights=${1%/}
  if [[ $weights == models/* && ! -e $weights && -n ${removed_models[${weights#models/}]:-} ]]; then
    restore_model "${weights#models/}"
  fi
}

# A run's resumable state is models/<run>-training (runs/base -> models/base-training), in the tree or in
# the history.
has_snapshot() {
  [[ -f models/$1-training/config.json || -n ${removed_models[$1-training]:-} ]]
}

# restore_run RUN: the state of models/RUN-training put back into runs/RUN.
restore_run() {
  local run=$1
  local dst=runs/$run snap=models/$run-training
  [[ -f $snap/config.json ]] || restore_model "$run-training"
  [[ -f $snap/config.json ]] || die 3 "no $snap to restore"
  [[ ! -e $dst ]] || die 3 "$dst exists; move it away to restore"
  mkdir -p "$dst.tmp"
  cp -r "$snap"/. "$dst.tmp/"
  rm -f "$dst.tmp/README.md" "$dst.tmp"/predicted_junctions.tar.gz.part* "$dst.tmp/learning_curves.png"
  if compgen -G "$snap/predicted_junctions.tar.gz.part*" >/dev/null; then
    cat "$snap"/predicted_junctions.tar.gz.part* | tar -C "$dst.tmp" -xzf -
  fi
  mv "$dst.tmp" "$dst"
  echo "$dst restored from $snap"
}

# resume_or_restore RUN: sets the array `resume` to (--resume) when runs/RUN has checkpoints, after putting
# back its snapshot when runs/RUN is missing (a lost machine costs one session).
resume_or_restore() {
  local run=$1
  if [[ ! -e runs/$run ]] && has_snapshot "$run"; then restore_run "$run"; fi
  resume=()
  [[ -d runs/$run/checkpoints ]] && resume=(--resume)
  return 0
}

# Links the meshes of the named split lists into DIR (lc2wf-dataset renders every mesh of one folder).
# The meshes' absolute folder is resolved once: a subshell per name took minutes at low priority.
link_meshes() {
  local dir=$1 from
  shift
  from=$(cd "$meshes" && pwd)
  mkdir -p "$dir"
  cat "$@" | while read -r name; do
    [[ -n "$name" ]] && ln -sfn "$from/$name.polyshape" "$dir/$name.polyshape"
  done
}

# score_cells WEIGHTS CLOUDS DIR CELL...: lc2wf-eval of WEIGHTS on the validation split of CLOUDS once per
# "tag:flags" cell into DIR/tag (a finished cell is kept, so a killed run resumes), then the table, best first.
score_cells() {
  local weights=$1 clouds=$2 dir=$3 cell
  shift 3
  mkdir -p "$dir"
  for cell in "$@"; do
    local tag=${cell%%:*} flags=${cell#*:}
    [[ -f $dir/$tag/metrics.json ]] && continue
    # shellcheck disable=SC2086  # flags are words
    "$build_dir/infer/lc2wf-eval" --weights "$weights" --data "$clouds" --split configs/splits/val.txt \
      --out "$dir/$tag.tmp" --method "$tag" --quiet $flags
    rm -rf "${dir:?}/$tag" && mv "$dir/$tag.tmp" "$dir/$tag"
  done
  /usr/bin/python3 experiments/selection_table.py "$dir" > "$dir/table.md"
  cat "$dir/table.md"
}

# score_on_val WEIGHTS PREFIX: lc2wf-eval of WEIGHTS on the validation split at 1 and 8 test-time views
# -> PREFIX1, PREFIX8 (metrics printed).
score_on_val() {
  local views
  for views in 1 8; do
    "$build_dir/infer/lc2wf-eval" --weights "$1" --data runs/dataset/clouds \
      --split configs/splits/val.txt --test-time-views "$views" -q -o "$2$views"
    cat "$2$views/metrics.md"
  done
}

# general_list MIX LIST PART...: links the clouds of runs/PART/clouds into runs/MIX/clouds and writes their
# names, sorted, to LIST (the training and validation lists of configs/general.json and its successors).
general_list() {
  local mix=$1 list=$2 part f
  shift 2
  mkdir -p "runs/$mix/clouds"
  for part in "$@"; do
    for f in runs/$part/clouds/*.lcloud; do ln -sfn "$(realpath "$f")" "runs/$mix/clouds/$(basename "$f")"; basename "$f" .lcloud; done
  done | sort -u > "$list"
}

# train_mix MIX RUN CONFIG [FLAGS...]: lc2wf-train CONFIG [FLAGS] into runs/RUN (resumed, or restored from its
# snapshot), once MIX's data step has written runs/MIX/train.txt.
train_mix() {
  local mix=$1 run=$2 config=$3 resume
  shift 3
  need_binary "$build_dir/train/lc2wf-train" lc2wf-train
  [[ -s runs/$mix/train.txt ]] || die 3 "no training list: run experiments/run.sh $mix-data first"
  resume_or_restore "$run"
  "$build_dir/train/lc2wf-train" "$config" "${resume[@]}" "$@"
}

# render_part MIX MESHES OUT [FLAGS...]: one part of a training mix as raster clouds (30 views, lc2wf-dataset's
# defaults and FLAGS, e.g. --names LIST) -> runs/MIX/OUT, its summary in runs/MIX/OUT.json; resumable
# (lc2wf-dataset skips the buildings it has done), and a failed building does not stop the step.
render_part() {
  local mix=$1 meshes_dir=$2 out=$3
  shift 3
  "$build_dir/tools/lc2wf-dataset" --meshes "$meshes_dir" --out "runs/$mix/$out" --renderer raster --views 30 -j 2 -q "$@" \
    > "runs/$mix/$out.json" || true
}

# metrics_row TAG FLAGS METRICS.JSON...: one markdown table row, "vAP / sAP / WED" per lc2wf-eval metrics file
# ("-" where a file does not exist), so every validation table of the lab reads the same.
metrics_row() {
  python3 - "$@" <<'PY'
import json, os, sys
tag, flags, paths = sys.argv[1], sys.argv[2], sys.argv[3:]
def cell(path):
    if not os.path.exists(path):
        return '-'
    m = json.load(open(path))
    return f"{100*m['vertex_avg']['ap']:.1f} / {100*m['edge_avg']['ap']:.1f} / {m['wed']['total_num']:.2f}"
print(f"| {tag} | {flags} | " + ' | '.join(cell(p) for p in paths) + ' |')
PY
}

# score_validation ROOT REAL_CLOUDS GEN_CLOUDS WEIGHTS TAG [FLAGS...]: the validation table of a mix (general2-val,
# general4-val): the real split's buildings of REAL_CLOUDS per group, the Roof-Image validation clouds, the
# generated validation buildings of GEN_CLOUDS and, once photo-data has rendered them, the photo-like validation
# clouds (runs/photo/realval-blender) -> ROOT/TAG and a row of ROOT/table.md.
score_validation() {
  local root=$1 real=$2 gen=$3 weights=$4 tag=$5 out
  shift 5
  out=$root/$tag
  mkdir -p "$out"
  bench/real/score_groups.sh "$weights" "$real" val "$out/real" "$@" > /dev/null
  [[ -f $out/ri/metrics.json ]] || "$build_dir/infer/lc2wf-eval" --weights "$weights" --data runs/general/rival-blender/clouds \
    --split runs/general/rival-names.txt -o "$out/ri" -q --method "$tag" "$@" > /dev/null
  [[ -s $out/gen-names.txt ]] || ls runs/general/genval-raster/clouds | sed -n 's/\.lcloud$//p' > "$out/gen-names.txt"
  [[ -f $out/gen/metrics.json ]] || "$build_dir/infer/lc2wf-eval" --weights "$weights" --data "$gen" \
    --split "$out/gen-names.txt" -o "$out/gen" -q --method "$tag" "$@" > /dev/null
  if [[ ! -f $out/photo/metrics.json ]] &&
    [[ $(ls runs/photo/realval-blender/clouds 2> /dev/null | wc -l) -eq $(wc -l < experiments/lists/photo-realval.txt) ]]; then
    "$build_dir/infer/lc2wf-eval" --weights "$weights" --data runs/photo/realval-blender/clouds \
      --split experiments/lists/photo-realval.txt -o "$out/photo" -q --method "$tag" "$@" > /dev/null
  fi
  metrics_row "$tag" "${*:--}" "$out"/real/eval/{all,height_ge20_m,source_vienna}/metrics.json "$out"/{ri,gen,photo}/metrics.json \
    >> "$root/table.md"
  tail -1 "$root/table.md"
}
