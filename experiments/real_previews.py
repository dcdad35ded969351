# The model card's three real test buildings: best, median and worst by edge F1 at 0.5 m among those with at
# least 16 GT edges, from an lc2wf-eval per_building.csv of the real test split; prints "rank name F1 source
# roof height" per line, for lc2wf-infer --preview.
#   python3 experiments/real_previews.py EVAL/per_building.csv [configs/splits/lod2/buildings.csv]
import csv, sys
per_building = sys.argv[1]
meta_csv = sys.argv[2] if len(sys.argv) > 2 else 'configs/splits/lod2/buildings.csv'
meta = {r['name']: r for r in csv.DictReader(open(meta_csv))}
scored = []
for r in csv.DictReader(open(per_building)):
    gt, pred, tp = int(r['gt_edges']), int(r['pred_edges']), int(r['edge_tp@0.50'])
    if gt < 16:
        continue
    f1 = 2 * tp / (gt + pred) if gt + pred else 0.0
    scored.append((f1, r['name']))
scored.sort(key=lambda x: (-x[0], x[1]))  # ties by name: the same choice every run
for rank, (f1, name) in (('best', scored[0]), ('median', scored[len(scored) // 2]), ('worst', scored[-1])):
    m = meta.get(name, {})
    print(rank, name, f'{f1:.2f}', m.get('source', '?'), m.get('roof_kind', '?'), m.get('height_m', '?'))
