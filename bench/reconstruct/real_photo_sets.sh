#!/usr/bin/env bash
# lc2wf-reconstruct on real photo sets of buildings, as a user runs it (COLMAP poses, scale from the evidence the
# photos carry), and one table row per set: photos, sizes, focal source, registered, 3D lines, scale source,
# junctions, edges, seconds. No ground truth: what the wireframes show is judged from their previews.
#   bench/reconstruct/real_photo_sets.sh WEIGHTS PHOTOS_ROOT OUT [LIST]
# LIST (default bench/reconstruct/real-photo-sets.txt): NAME [TAB FLAGS]; a name ending in -calibrated reads
# the photos of NAME without that suffix. A finished set (OUT/NAME/report.json) is kept. Writes OUT/table.md.
set -euo pipefail
[[ $# -ge 3 ]] || { sed -n 2,7p "$0"; exit 2; }
weights=$1 root=$2 out=$3 list=${4:-$(dirname "$0")/real-photo-sets.txt}
bin=${BUILD_DIR:-build}/reconstruct/lc2wf-reconstruct
[[ -x $bin ]] || { echo "no $bin: build first" >&2; exit 3; }
mkdir -p "$out"
while IFS=$'\t' read -r name flags; do
  [[ -z $name || $name == \#* ]] && continue
  photos=$root/${name%-calibrated}/images
  [[ -d $photos ]] || { echo "$name: no $photos" >&2; continue; }
  if [[ ! -f $out/$name/report.json ]]; then
    # shellcheck disable=SC2086  # the flags are words
    "$bin" "$photos" --weights "$weights" -o "$out/$name" -j "${THREADS:-2}" $flags 2> "$out/$name.log" || echo "$name: exit $?" >&2
  fi
done < "$list"
/usr/bin/python3 - "$out" "$list" <<'PY' | tee "$out/table.md"
import json, os, sys
out, listing = sys.argv[1], sys.argv[2]
print('| set | flags | photos (sizes) | focal length | registered | 3D lines (confirmed) | scale from | junctions / edges | seconds |')
print('|---|---|---|---|---|---|---|---|---|')
for line in open(listing):
    if not line.strip() or line.startswith('#'): continue
    name, _, flags = line.rstrip('\n').partition('\t')
    path = os.path.join(out, name, 'report.json')
    if not os.path.exists(path):
        print(f'| {name} | {flags or "–"} | – | – | – | – | – | stopped (see {name}.log) | – |'); continue
    r = json.load(open(path))
    sizes = {tuple(s) for s in r['images']['sizes']}
    cams = r['cameras']
    source = r['images'].get('focal_source', '?')
    guessed = source == 'the default' or source.startswith('EXIF (')
    focal = source + (' (refined)' if cams.get('focal_refined') else ' (kept: no model with it free)' if guessed else '')
    print(f"| {name} | {flags or '–'} | {r['images']['read']} ({len(sizes)} size{'s' if len(sizes) > 1 else ''}) | {focal} | "
          f"{cams['registered']} | {r['lines_3d']} ({r['lines_3d'] - r.get('lines_unconfirmed', 0)}) | {r['frame']['scale_source']} | "
          f"{r['junctions']} / {r['edges']} | {r['seconds']['total']:.0f} |")
PY
