"""The pieces of `ldmbench report` (scripts/report/ldmbench_report.py):

runs     reading run folders / records files into one tidy table, and back from tidy.csv
table    typed views of that table: numbers, statuses, methods, axes, metric columns
figures  the plots (matplotlib, Agg): trade-offs, memory, sub-pass bars, scaling
grids    image grids after the thesis's Tables 3-9, from the PNGs a run wrote
pages    the summary tables, summary.md and index.html
"""
