"""Copies of a scene file with one light source each (each light alone, the environment alone),
to measure a light's share of an error by itself. Used by lights_cycles.sh and
lights_mustshow.py."""

import json
import os
import sys


def one_source_specs(spec):
    """(label, spec) for each light of a scene spec alone and for its environment alone; an
    empty list when the scene has fewer than two sources (the variant would be the scene)."""
    sources = [("light", i) for i in range(len(spec.get("lights", [])))]
    if "environment" in spec:
        sources.append(("environment", None))
    if len(sources) < 2:
        return []
    out = []
    for kind, i in sources:
        copy = dict(spec)
        if kind == "light":
            copy["lights"] = [spec["lights"][i]]
            copy.pop("environment", None)
            label = spec["lights"][i].get("name", f"light{i}")
        else:
            copy["lights"] = []
            label = "environment"
        out.append((label, copy))
    return out


def write_variants(spec, out_dir, base):
    """Writes each one-source variant as out_dir/BASE.only-LABEL.json; returns (label, path)."""
    written = []
    for label, copy in one_source_specs(spec):
        path = os.path.join(out_dir, f"{base}.only-{label}.json")
        with open(path, "w") as f:
            json.dump(copy, f, indent=1)
        written.append((label, path))
    return written


if __name__ == "__main__":
    # light_variants.py SCENE.json: writes the variants beside the scene, prints their paths.
    scene = sys.argv[1]
    with open(scene) as f:
        variants = write_variants(json.load(f), os.path.dirname(scene),
                                  os.path.splitext(os.path.basename(scene))[0])
    for _, path in variants:
        print(path)
