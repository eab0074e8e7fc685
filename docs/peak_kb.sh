# Sourced by docs/csg-scale/run.sh and docs/droplets/run.sh: peak memory without GNU time.
# peak_kb CMD...: runs CMD; prints its peak resident set in kB (the kernel's high-water mark VmHWM in
# /proc/PID/status, read every 10 ms until it exits: what GNU time's %M reports); fails as CMD fails
peak_kb() {
    "$@" &
    pid=$!
    kb=0
    while [ -r "/proc/$pid/status" ]; do
        hwm=
        while read -r key val _; do
            [ "$key" = VmHWM: ] && { hwm=$val; break; }
        done <"/proc/$pid/status"
        [ -n "$hwm" ] || break # exited: a zombie has no memory
        kb=$hwm
        sleep 0.01
    done
    wait "$pid" || return 1
    echo "$kb"
}
