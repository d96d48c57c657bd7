#!/bin/bash
# A database name is a file name, whatever it looks like: Debian's SQLite
# reads a name beginning "file:" as a URI (so "file:u.db" made u.db, and
# a real file named "file:v.db" could not be opened), and ":memory:" as
# no file at all (then refused as "cannot switch to WAL"). The checks
# before opening (header, same file) looked at the named file while SQLite
# opened another: `import --db file:a.db a.db` imported a.db into itself.
set -u
BUILD=$1
. "$(dirname "$0")/common.bash"
failShowsOutput
needBuilt earc-db
DB="$BUILD/earc-db"
cd "$WORK"

"$DB" build --db file:u.db --kind mobile --count 3 --seed 2 --threads 1 -q > out 2> err || fail "build --db file:u.db"
[ -f "file:u.db" ] || fail "build --db file:u.db made no file of that name: $(ls)"
[ -e u.db ] && fail "build --db file:u.db made u.db"
"$DB" inspect --db file:u.db > out 2> err || fail "inspect --db file:u.db"
grep -q "^database  file:u.db" out || fail "inspect names another file"
rows=$(sqlValue "$WORK/file:u.db" "SELECT count(*) FROM experiences")
[ "$rows" -gt 0 ] || fail "no rows in file:u.db"

# A file of that name made elsewhere opens as itself.
cp "file:u.db" plain.db
mv plain.db "file:v.db"
"$DB" verify --db file:v.db > out 2> err || fail "verify --db file:v.db"

# Import from a file into a name that only looks like it: a new file.
cp "file:u.db" a.db
before=$(md5sum < a.db)
"$DB" import --db file:a.db a.db -q > out 2> err || fail "import --db file:a.db a.db"
[ "$(sqlValue "$WORK/file:a.db" "SELECT count(*) FROM experiences")" = "$rows" ] || fail "file:a.db lacks a.db's rows"
[ "$(md5sum < a.db)" = "$before" ] || fail "a.db changed"
# And into the very same file: refused, as for any other name of it.
refusedInOneLine "same file" "$DB" import --db "./file:a.db" "file:a.db"

# ":memory:" is a file here too.
"$DB" build --db :memory: --kind mobile --count 3 --seed 2 --threads 1 -q > out 2> err || fail "build --db :memory:"
[ -f ":memory:" ] || fail "build --db :memory: made no file of that name"
"$DB" verify --db :memory: > out 2> err || fail "verify --db :memory:"
echo "ok"
