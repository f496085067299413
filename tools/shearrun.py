"""One `stiction asperity --shear --json` run as a measurement: its JSON, wall
time, CPU time and peak memory (the child's own, from wait4), for the make
bench scripts."""
import json
import os
import subprocess
import tempfile
import time


def run_shear(cli, args):
    """(json, wall s, cpu s, peak MB) of `CLI asperity --shear --model 3d
    --json ARGS`, or (None, wall s, cpu s, reason) when it fails."""
    with tempfile.TemporaryFile("w+") as fo, tempfile.TemporaryFile("w+") as fe:
        t0 = time.monotonic()
        p = subprocess.Popen([cli, "asperity", "--shear", "--model", "3d", "--json"] + args,
                             stdout=fo, stderr=fe, text=True)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.monotonic() - t0
        code = os.waitstatus_to_exitcode(status)
        fo.seek(0), fe.seek(0)
        out, err = fo.read(), fe.read().strip()
    cpu = ru.ru_utime + ru.ru_stime
    if code != 0:
        return None, wall, cpu, err.splitlines()[-1] if err else "exit %d" % code
    j = json.loads(out)
    return (j[-1] if isinstance(j, list) else j), wall, cpu, ru.ru_maxrss / 1024.0
