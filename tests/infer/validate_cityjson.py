#!/usr/bin/env python3
"""Validates CityJSON files against the CityJSON 2.0 schemas in SCHEMA_DIR (draft-07, python3-jsonschema) and
checks that every Solid shell is closed and consistently oriented. Prints one line per file; exit 1 on any failure."""
import json
import pathlib
import sys
import warnings

import jsonschema


def load_validator(schema_dir):
    store = {}
    for path in pathlib.Path(schema_dir).glob("*.schema.json"):
        schema = json.loads(path.read_text())
        store[schema["$id"]] = schema
    root = json.loads((pathlib.Path(schema_dir) / "cityjson.schema.json").read_text())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        resolver = jsonschema.RefResolver(base_uri=root["$id"], referrer=root, store=store)
    return jsonschema.Draft7Validator(root, resolver=resolver)


def shell_problems(doc):
    problems = []
    for name, obj in doc["CityObjects"].items():
        for geometry in obj.get("geometry", []):
            if geometry["type"] != "Solid":
                continue
            for shell in geometry["boundaries"]:
                runs = {}
                for surface in shell:
                    ring = surface[0]
                    for a, b in zip(ring, ring[1:] + ring[:1]):
                        runs[(a, b)] = runs.get((a, b), 0) + 1
                for (a, b), n in runs.items():
                    if n != 1 or runs.get((b, a), 0) != 1:
                        problems.append(f"{name}: side {a}-{b} is not run once each way")
            values = geometry["semantics"]["values"]
            if [len(v) for v in values] != [len(s) for s in geometry["boundaries"]]:
                problems.append(f"{name}: one semantic value per surface expected")
    return problems


def main():
    validator = load_validator(sys.argv[1])
    failed = 0
    for path in sys.argv[2:]:
        doc = json.loads(pathlib.Path(path).read_text())
        errors = [f"{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in validator.iter_errors(doc)]
        errors += shell_problems(doc)
        print(f"{pathlib.Path(path).name}: {'ok' if not errors else 'INVALID'}")
        for e in errors[:10]:
            print("  " + e)
        failed += bool(errors)
    if len(sys.argv) < 3:
        print("no files given")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
