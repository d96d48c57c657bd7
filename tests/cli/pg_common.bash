# Sourced by the pg_*.sh tests after common.bash (not a test itself): a
# PostgreSQL server of the test's own, started by tools/postgres-dev.sh in
# a temporary directory (as nobody when run as root), on a Unix socket
# there and on 127.0.0.1 at a free port, and stopped when the test exits,
# however it ends. Sets PG_DIR, PG_URI (socket) and PG_TCP_URI. Skipped
# (77) without PostgreSQL's server programs (tools/setup.sh --tests).
PG_SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ls /usr/lib/postgresql/*/bin/initdb > /dev/null 2>&1 ||
  { echo "skipped: no PostgreSQL server programs (tools/setup.sh --tests installs them)"; exit 77; }
# The cluster in memory (/dev/shm) when there is room for it there: its
# files are written and removed often, which costs a disk much more.
PG_PARENT=/tmp
if [ -w /dev/shm ] && [ "$(df -Pk /dev/shm 2> /dev/null | awk 'NR == 2 {print $4}')" -ge 1048576 ] 2> /dev/null; then
  PG_PARENT=/dev/shm
fi
PG_DIR=$(mktemp -u "$PG_PARENT/earc-pg-test.XXXXXX")
trap 'bash "$PG_SRC/tools/postgres-dev.sh" stop "$PG_DIR"; rm -rf "$WORK"' EXIT
EARC_PG_OPTIONS="-c fsync=off" bash "$PG_SRC/tools/postgres-dev.sh" start "$PG_DIR" > "$WORK/pg-start.out" 2>&1 ||
  { echo "FAIL: the test's PostgreSQL server did not start: $(tail -n 3 "$WORK/pg-start.out")"; exit 1; }
PG_URI=$(cat "$PG_DIR/uri-socket")
PG_TCP_URI=$(cat "$PG_DIR/uri-tcp")
# pgValue URI SQL: the query's one value.
pgValue() { psql -X -A -t -q "$1" -c "$2"; }
# pgNewDatabase NAME: a new empty database on the server; its TCP URI.
pgNewDatabase() {
  pgValue "$PG_TCP_URI" "CREATE DATABASE $1" > /dev/null || fail "cannot create database $1"
  echo "${PG_TCP_URI%/*}/$1"
}
