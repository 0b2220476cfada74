"""Helpers shared by the scripts in scripts/ (drawing is viz/; everything else two scripts
need is here):

  paths      ROOT, find_disco() (build tree, installed layout, PATH), scene files by name
  arguments  argparse types (int_at_least, int_in_range, comma_list) and the --disco option
  solve      one `disco solve` run (wall and CPU time, solution.json, its log) and the lines
             of the solve log; `disco --version`
  search     `mpirun ... disco search`, scripts/bench_paper runs, and reading a search's
             outputs (best.json, runs.jsonl, paper_table.csv)
  tables     fmt, Markdown tables, CSV files, log-log fits
  results    the results file of a benchmark (scripts/results/NAME.md): a generated header
             per run and one section per configuration label

The scripts import them as `from common.solve import solve` after putting their own folder
first on sys.path (as they do for viz).
"""
