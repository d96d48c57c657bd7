#!/bin/bash
# earc-bench refuses, in one line with exit status 2 and before it changes
# anything on disk, a results database that is not one (not SQLite, another
# application's SQLite file, a 0-byte file to a reader) or is damaged (a
# table of its schema missing, or a column),
# in every subcommand that reads one, and an output directory named like a
# file (plot -o fig.png) or that is a file. Skipped (77) without
# /usr/bin/python3.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
BENCH="$BUILD/earc-bench"
needBuilt earc-bench
needPython
mkdir "$WORK/d" && cd "$WORK/d" || exit 1

# A results database with one recorded Lightning database in it (a second).
"$BENCH" lightning-db --suite mobile --robots 2 --count 1 --problem-time-limit 0.5 -o l.lightning --results r.sqlite \
  > /dev/null || fail "lightning-db exited $?"
touch a-file empty.sqlite
echo "not a database" > text.txt
"$PY" - <<'PYEOF' || fail "could not make the bad databases"
import sqlite3
c = sqlite3.connect("foreign.sqlite"); c.execute("CREATE TABLE t(x)"); c.commit(); c.close()
c = sqlite3.connect("r.sqlite"); c.execute("PRAGMA wal_checkpoint(TRUNCATE)"); c.close()
for table in ("trials", "databases"):
    c = sqlite3.connect("no-%s.sqlite" % table)
    sqlite3.connect("r.sqlite").backup(c)
    c.execute("DROP TABLE %s" % table); c.commit(); c.close()
c = sqlite3.connect("no-column.sqlite")
sqlite3.connect("r.sqlite").backup(c)
c.execute("ALTER TABLE trials DROP COLUMN makespan"); c.commit(); c.close()
PYEOF
dirSnapshot > "$WORK/before"

refused() {  # refused TEXT ARGS...: exit 2, one line on stderr containing TEXT, nothing changed
  refusedInOneLine "$1" "$BENCH" "${@:2}"
  dirSnapshot | cmp -s - "$WORK/before" || fail "earc-bench ${*:2} changed the directory: $(dirSnapshot | diff "$WORK/before" -)"
}

for f in no-trials no-databases foreign text; do
  case $f in
    no-*) file=$f.sqlite; want="$file: damaged database file (table ${f#no-} is missing; schema version 9 has it)" ;;
    foreign) file=$f.sqlite; want="$file: not an earc-bench results database" ;;
    text) file=text.txt; want="$file: cannot open the results database: not a SQLite database" ;;
  esac
  refused "$want" table --results "$file"
  refused "$want" export --results "$file" --csv out.csv
  refused "$want" plot --results "$file" -o figures
  refused "$want" run --suites mobile --robots 2 --methods arc --trials 1 --results "$file"
  refused "$want" lightning-db --suite mobile --robots 2 --count 1 -o new.lightning --results "$file"
done
# A 0-byte file, in the experience store's words, by the commands that only
# read results (run would make it a results database).
want="empty.sqlite: empty file (0 bytes), not an earc-bench results database yet"
refused "$want" table --results empty.sqlite
refused "$want" export --results empty.sqlite --csv out.csv
refused "$want" plot --results empty.sqlite -o figures
# A table without a column this program reads: named in one line, no SQL.
want="no-column.sqlite: damaged database file (table trials has no column named makespan; its schema version has it)"
refused "$want" table --results no-column.sqlite
refused "$want" export --results no-column.sqlite --csv out.csv
refused "$want" run --suites mobile --robots 2 --methods arc --trials 1 --results no-column.sqlite
refused "$want" lightning-db --suite mobile --robots 2 --count 1 -o new.lightning --results no-column.sqlite

refused "fig.png: -o: names the directory the files go into, not a .png file" plot --results r.sqlite -o fig.png
refused "a-file: -o: exists and is not a directory" plot --results r.sqlite -o a-file
refused "logs.log: --ompl-log: names the directory the files go into, not a .log file" \
  export --results r.sqlite --ompl-log logs.log
refused "a-file: --ompl-log: exists and is not a directory" export --results r.sqlite --ompl-log a-file
echo "ok"
