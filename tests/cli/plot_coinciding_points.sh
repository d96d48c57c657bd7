#!/bin/bash
# label: unsanitized
# tools/plots/plot_results.py's time figure gives each method its own
# marker and moves each method's points a little aside, so that methods
# of equal times both show: E-ARC's points once lay exactly under ARC's,
# with the same marker, and could not be seen.
# Trials made up in Python; skipped (77) without /usr/bin/python3 with
# matplotlib.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needMatplotlib

"$PY" - "$SRC/tools/plots" "$WORK" <<'PYEOF' || fail "methods of equal times hide each other in the time figure"
import sys
sys.path.insert(0, sys.argv[1])
import plot_results as pr
T = pr.Trial
rows = []
for n in (2, 4, 8):
    for method in ("earc", "arc", "coupled"):  # the same times, as at 2 robots in the paper's suites
        for t in (0.001, 0.002, 0.003):
            rows.append(T("mobile", 3.0, n, method, True, t * n, ()))
rows.append(T("mobile", 3.0, 8, "coupled", False, 3.0, ()))  # one cell drawn hollow
figures = []
real_save = pr.save
def keep(fig, out, name):
    figures.append(fig)
    return real_save(fig, out, name)
pr.save = keep
pr.plot_times(rows, "mobile", "mobile", sys.argv[2])
ax = figures[0].axes[0]
lines = {l.get_label(): l for l in ax.get_lines() if not l.get_label().startswith("_")}
earc, arc, coupled = lines["E-ARC"], lines["ARC"], lines["Coupled RRT-Connect"]
markers = [l.get_marker() for l in (earc, arc, coupled)]
assert len(set(markers)) == 3, markers
for a, b in ((earc, arc), (arc, coupled)):
    assert list(a.get_ydata()) == list(b.get_ydata())  # equal times...
    for x, y in zip(a.get_xdata(), b.get_xdata()):     # ...drawn side by side, at most 5% apart
        assert x < y <= 1.05 * x, (a.get_label(), x, b.get_label(), y)
# The hollow cell is coupled's marker at coupled's place.
hollow = [l for l in ax.get_lines() if l.get_markerfacecolor() == "white" and l.get_label().startswith("_")]
assert len(hollow) == 1 and hollow[0].get_marker() == coupled.get_marker(), [l.get_marker() for l in hollow]
assert hollow[0].get_xdata()[0] == coupled.get_xdata()[-1], (hollow[0].get_xdata(), coupled.get_xdata())
# Ticks stay on the robot counts.
assert list(ax.get_xticks()) == [2, 4, 8], ax.get_xticks()
PYEOF
echo "ok"
