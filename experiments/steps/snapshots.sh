# Steps snapshot and restore: a run's resumable state as models/RUN-training, so a lost machine costs one
# session (sourced by experiments/run.sh).

# snapshot [RUN]: the newest checkpoint of each stage, best weights, log and hand-off of runs/RUN (default
# base) copied to models/RUN-training.
step_snapshot() {
  local run=${1:-base}
  local src=runs/$run snap=models/$run-training
  [[ -f $src/config.json ]] || die 3 "no training run in $src"
  local tmp=$snap.tmp
  rm -rf "$tmp" && mkdir -p "$tmp/checkpoints"
  cp "$src/config.json" "$src/log.jsonl" "$tmp/"
  for stage in junction edge; do
    [[ -f $src/$stage.safetensors ]] && cp "$src/$stage.safetensors" "$tmp/"
    # The newest complete slot: its weights and optimiser state are written together.
    local newest
    newest=$(ls -t "$src"/checkpoints/${stage}_last_?.safetensors 2>/dev/null | head -1 || true)
    [[ -n "$newest" && -f "${newest%.safetensors}.optim.safetensors" ]] || continue
    cp "$newest" "$tmp/checkpoints/${stage}_last_0.safetensors"
    cp "${newest%.safetensors}.optim.safetensors" "$tmp/checkpoints/${stage}_last_0.optim.safetensors"
  done
  # The hand-off is the edge stage's input: kept, or a restored run would predict it again and drop the edge
  # stage's log lines. In parts of 19 MB: a committed file may have 20 MB at most.
  [[ -f $src/predicted_junctions/manifest.json ]] &&
    tar -C "$src" -czf - predicted_junctions | split -b 19m -d - "$tmp/predicted_junctions.tar.gz.part"
  local step=$run
  case $run in base) step=train ;; local-labels) step=local ;; dense) step=dense-train ;; esac
  sed "s|@RUN@|$run|g; s|@STEP@|$step|g" experiments/training-snapshot.md > "$tmp/README.md"
  # The learning curves so far, shown in the top README (skipped without matplotlib).
  /usr/bin/python3 tools/plots/plot_training.py "$src" --out "$tmp/learning_curves.png" >/dev/null ||
    echo "experiments/run.sh: no learning curves (tools/setup-deps.sh installs python3-matplotlib)" >&2
  rm -rf "$snap" && mv "$tmp" "$snap"
  echo "Training state of $src copied to $snap ($(du -sh "$snap" | cut -f1))"
}

# restore [RUN]: models/RUN-training (from the git history when it left the tree) back into runs/RUN.
step_restore() { restore_run "${1:-base}"; }
