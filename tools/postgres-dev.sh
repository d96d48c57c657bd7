#!/usr/bin/env bash
# A PostgreSQL server of one's own for the PostgreSQL experience store:
# a new cluster in DIR (initdb), listening on a Unix socket in DIR and on
# 127.0.0.1 at a free port, with a database "earc" of a role "earc" that
# logs in without a password (trust; local connections only).
#   tools/postgres-dev.sh start DIR     prints the two URIs (socket, TCP)
#   tools/postgres-dev.sh stop DIR      stops the server and removes DIR
#   tools/postgres-dev.sh restart DIR   restarts it (fast shutdown)
# Then: earc-db build --db "$(cat DIR/uri-tcp)" ...
# PostgreSQL refuses to run as root: as root, the server runs as
# $EARC_PG_USER (default nobody), which DIR is handed to. Extra server
# options in $EARC_PG_OPTIONS (the tests pass "-c fsync=off").
set -euo pipefail
cmd=${1:-}
dir=${2:-}
[ -n "$cmd" ] && [ -n "$dir" ] || { echo "usage: $0 start|stop|restart DIR" >&2; exit 2; }
bin=${EARC_PG_BIN:-$(ls -d /usr/lib/postgresql/*/bin 2> /dev/null | sort -V | tail -n 1)}
[ -x "$bin/initdb" ] || { echo "$0: no PostgreSQL server programs (apt-get install postgresql)" >&2; exit 2; }
as=()
if [ "$(id -u)" = 0 ]; then
  user=${EARC_PG_USER:-nobody}
  as=(runuser -u "$user" --)
fi
run() { "${as[@]}" "$@"; }

freePort() {
  /usr/bin/python3 -c 'import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

case $cmd in
  start)
    [ ! -e "$dir/data" ] || { echo "$0: $dir already holds a cluster" >&2; exit 2; }
    mkdir -p "$dir"
    dir=$(cd "$dir" && pwd)
    chmod 755 "$dir"
    [ ${#as[@]} -eq 0 ] || chown "$user" "$dir"
    run test -w "$dir" ||
      { echo "$0: $dir: ${user:-this user} cannot write there (a private parent directory?); choose one under /tmp" >&2; exit 2; }
    run "$bin/initdb" -D "$dir/data" -U earc --auth=trust --no-sync -E UTF8 --locale=C > "$dir/initdb.log" 2>&1 ||
      { echo "$0: initdb failed: $(tail -n 3 "$dir/initdb.log")" >&2; exit 1; }
    for attempt in 1 2 3; do
      port=$(freePort)
      if run "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 30 \
        -o "-k $dir -p $port -h 127.0.0.1 -c max_connections=60 ${EARC_PG_OPTIONS:-}" start > /dev/null; then
        break
      fi
      [ $attempt -lt 3 ] || { echo "$0: the server did not start: $(tail -n 3 "$dir/server.log")" >&2; exit 1; }
    done
    echo "$port" > "$dir/port"
    run "$bin/createdb" -h "$dir" -p "$port" -U earc earc
    socket_host=$(/usr/bin/python3 -c 'import sys, urllib.parse; print(urllib.parse.quote(sys.argv[1], safe=""))' "$dir")
    echo "postgresql://earc@$socket_host:$port/earc" > "$dir/uri-socket"
    echo "postgresql://earc@127.0.0.1:$port/earc" > "$dir/uri-tcp"
    cat "$dir/uri-socket" "$dir/uri-tcp"
    ;;
  stop)
    [ -d "$dir/data" ] && run "$bin/pg_ctl" -D "$dir/data" -m immediate -w stop > /dev/null 2>&1 || true
    rm -rf "$dir"
    ;;
  restart)
    run "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -m fast -w -t 30 restart > /dev/null
    ;;
  *)
    echo "usage: $0 start|stop|restart DIR" >&2
    exit 2
    ;;
esac
