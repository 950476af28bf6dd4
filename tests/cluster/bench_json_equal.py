"""Compares two bench.json files apart from what depends on the machine and the schedule (timings, the merge's
sources, the shard); exits 1 with the first difference. Usage: bench_json_equal.py A B"""
import json
import sys


def normalised(path):
    with open(path, encoding="utf-8") as f:
        bench = json.load(f)
    for key in ("timing", "merged_from", "shard"):
        bench.pop(key, None)
    for entry in bench.get("scenarios", []):
        entry.pop("timing", None)
    return bench


def first_difference(a, b, where="bench"):
    if type(a) is not type(b):
        return f"{where}: {a!r} != {b!r}"
    if isinstance(a, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{where}.{key}: only in {'the second' if key in b else 'the first'}"
            found = first_difference(a[key], b[key], f"{where}.{key}")
            if found:
                return found
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{where}: {len(a)} items != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            found = first_difference(x, y, f"{where}[{i}]")
            if found:
                return found
        return None
    return None if a == b else f"{where}: {a!r} != {b!r}"


if __name__ == "__main__":
    difference = first_difference(normalised(sys.argv[1]), normalised(sys.argv[2]))
    if difference:
        print("bench_json_equal:", difference)
        sys.exit(1)
