#!/usr/bin/env bash
# The CityJSON files lc2wf writes, validated against the official CityJSON 2.0 schema with python3-jsonschema,
# then checked for what the schema cannot say (a Solid is closed: every side in two faces, run both ways).
# Exit 77 (skip) only when python3-jsonschema is missing.
set -euo pipefail
fixtures="$1"
schema_dir="$2"
python3 -c 'import jsonschema' 2>/dev/null || { echo "python3-jsonschema is not installed (tools/setup-deps.sh): skipped"; exit 77; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$fixtures" "$out"
python3 "$(dirname "$0")/validate_cityjson.py" "$schema_dir" "$out"/*.city.json
