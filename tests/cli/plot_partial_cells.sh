#!/bin/bash
# label: unsanitized
# tools/plots/plot_results.py's time figure draws the median over the
# solved trials only, so it marks what that leaves out: a cell where some
# trials failed is hollow and labelled "k/n", one where all failed is an x
# labelled "0/n" on the time limit's line, and the title gives the trials
# per cell and the limit. (The figure once showed a cell that solved 1 of
# 3 as an ordinary point, and a cell of none not at all.) Trials made up
# in Python; skipped (77) without /usr/bin/python3 with matplotlib.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needMatplotlib

"$PY" - "$SRC/tools/plots" "$WORK" <<'PYEOF' || fail "the time figure does not mark partly solved cells"
import re, sys
sys.path.insert(0, sys.argv[1])
import plot_results as pr
T = pr.Trial
rows = []
for n, times in ((4, [0.01, 0.02, 0.03]), (8, [1.4, None, None]), (16, [None, None, None])):
    for t in times:
        rows.append(T("mobile-obst", 3.0, n, "coupled", t is not None, t if t is not None else 3.0, ()))
        rows.append(T("mobile-obst", 3.0, n, "arc", True, 0.01 * n, ()))
cells = pr.time_cells(rows, "coupled")
assert [(n, k, total) for n, k, total, _ in cells] == [(4, 3, 3), (8, 1, 3), (16, 0, 3)], cells
assert cells[1][3] == (1.4, 1.4, 1.4) and cells[2][3] is None, cells
pr.plot_times(rows, "mobile-obst", "mobile-obst", sys.argv[2])
svg = open(sys.argv[2] + "/time_mobile-obst.svg").read()
# matplotlib draws text as paths, each after a comment holding the text.
texts = re.findall(r"<!-- (.*?) -->", svg)
for want in ("1/3", "0/3", "time limit 3 s", "k/n: k of n trials solved", "none solved"):
    assert want in texts, (want, texts)
assert "3/3" not in texts, texts  # a cell where every trial solved is not labelled
assert any("3 trials per cell, time limit 3 s" in t for t in texts), texts

# Two methods that solved none at the same robot count: their x marks
# nearly coincide on the limit's line, so their labels are stacked, not
# drawn over each other (each label's text follows its comment, placed by
# a translate).
for _ in range(3):
    rows.append(T("mobile-obst", 3.0, 16, "lightning", False, 3.0, ()))
pr.plot_times(rows, "mobile-obst", "mobile-obst", sys.argv[2])
svg = open(sys.argv[2] + "/time_mobile-obst.svg").read()
ys = [float(re.search(r"translate\(([-\d.]+) ([-\d.]+)\)", m.group(1)).group(2))
      for m in re.finditer(r"<!-- 0/3 -->(.{0,800})", svg, re.S)]
assert len(ys) == 2, ys
assert abs(ys[0] - ys[1]) >= 6, ys  # about a line of x-small text apart
PYEOF
echo "ok"
