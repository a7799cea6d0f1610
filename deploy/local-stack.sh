#!/usr/bin/env bash
# Starts the whole ambid service on this machine over the loopback DDS profile: the plant
# daemon (simulated bearing), the identifier and the diagnostics daemon, each its own process.
#   deploy/local-stack.sh start [DOMAIN] [RUNDIR]   starts the daemons in the background
#   deploy/local-stack.sh stop  [DOMAIN] [RUNDIR]   stops them (SIGTERM, by their pid files)
# Environment: AMBID (the binary, default build/services/ambid), AMBID_DDS_PLANT,
# AMBID_DDS_IDENTIFIER, AMBID_DDS_DIAGNOSTICS (fastdds | cyclone, default cyclone), AMBID_CONFIG
# (the folder of plant.json, identifier.json, diagnostics.json; default deploy/config).
# Logs: RUNDIR/<daemon>.log; trend store: RUNDIR/trend.sqlite.
set -euo pipefail
cd "$(dirname "$0")/.."

action=${1:?usage: deploy/local-stack.sh start|stop [DOMAIN] [RUNDIR]}
domain=${2:-42}
rundir=${3:-runs/stack}
ambid=${AMBID:-build/services/ambid}
config=${AMBID_CONFIG:-deploy/config}

case "$action" in
  start)
    mkdir -p "$rundir"
    # The diagnostics config with its trend store moved into RUNDIR.
    sed "s|\"store\": *\"[^\"]*\"|\"store\": \"$rundir/trend.sqlite\"|" "$config/diagnostics.json" \
      >"$rundir/diagnostics.json"
    for daemon in diagnostics identifier plant; do
      var="AMBID_DDS_${daemon^^}"
      cfg="$config/$daemon.json"
      [[ $daemon == diagnostics ]] && cfg="$rundir/diagnostics.json"
      "$ambid" daemon "$daemon" --dds "${!var:-cyclone}" --domain "$domain" --config "$cfg" \
        >"$rundir/$daemon.log" 2>&1 &
      echo $! >"$rundir/$daemon.pid"
    done
    ;;
  stop)
    for daemon in plant identifier diagnostics; do
      if [[ -f $rundir/$daemon.pid ]]; then
        pid=$(cat "$rundir/$daemon.pid")
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done  # up to 5 s
        rm -f "$rundir/$daemon.pid"
      fi
    done
    ;;
  *) echo "usage: deploy/local-stack.sh start|stop [DOMAIN] [RUNDIR]" >&2; exit 2 ;;
esac
