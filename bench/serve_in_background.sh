# Sourced by the bench scripts and the script tests: serve_in_background ORBIT LOG
# [SERVE_ARGS...] starts `ORBIT serve --listen 127.0.0.1:0 SERVE_ARGS...` in the background, its
# output in LOG, and waits (up to $serve_wait_seconds, 30 s unless the caller sets it) until it
# says where it listens; sets server_pid and address ("127.0.0.1:PORT"). Exits with the server's
# log when it does not start.
serve_in_background() {
  local orbit=$1 log=$2
  shift 2
  # The log exists before the first look at it: the server's own redirection may come later.
  : >"$log"
  "$orbit" serve --listen 127.0.0.1:0 "$@" >"$log" 2>&1 &
  server_pid=$!
  address=""
  for _ in $(seq $((${serve_wait_seconds:-30} * 10))); do
    address=$(sed -n 's/.*listening on \(127\.0\.0\.1:[0-9]*\).*/\1/p' "$log" | head -1)
    [[ -n "$address" ]] && return 0
    sleep 0.1
  done
  echo "orbit serve did not start:" >&2
  cat "$log" >&2
  exit 1
}
