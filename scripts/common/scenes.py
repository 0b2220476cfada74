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
