"""Scene sets the benchmarks share."""

# The start set (scripts/bench_starts, scripts/bench_kkt): starts 0, 1 and 2 (seed 1) of each.
START_SET = {
    "A3": "configs/scenarios/paper/A3.yaml",
    "A4": "configs/scenarios/paper/A4.yaml",
    "B1": "configs/scenarios/paper/B1.yaml",
    "B2": "configs/scenarios/paper/B2.yaml",
    "B3": "configs/scenarios/paper/B3.yaml",
    "contact": "configs/scenarios/three_robots_contact.yaml",
}


def other_scenes(root):
    """The other starts' scenes (scripts/bench_starts --others): every scene in
    configs/scenarios/ and configs/stress/, and paper A1 and A2, as {name: path from root};
    a stress scene's name is stress/NAME."""
    import glob
    import os
    out = {}
    for folder, prefix in (("configs/scenarios", ""), ("configs/stress", "stress/")):
        for path in sorted(glob.glob(os.path.join(root, folder, "*.yaml"))):
            out[prefix + os.path.basename(path)[:-len(".yaml")]] = os.path.relpath(path, root)
    for name in ("A1", "A2"):
        out[name] = f"configs/scenarios/paper/{name}.yaml"
    return out
