"""A class on one machine: N students through a real JupyterHub, timed and weighed (a script; nothing asserted).

Starts what tests/hub starts (tests/hub/hubctl.py: the edition on a local git server, the image's
environment from its ``binder/requirements.txt``, ``jupyterhub`` on 127.0.0.1 with the dummy
authenticator and ``LocalProcessSpawner``, one system user per student), then drives every student
through the Hub's REST API and the Jupyter Server API, all at once (``--at-once``, default: all):

1. start the student's server (``POST /hub/api/users/NAME/server``) and wait until it is ready;
2. pull the edition with nbgitpuller (its ``git-pull/api``, what the link's page calls);
3. open a session for lecture 01 and run its code cells through the kernel's websocket;
4. open a session for exercise 3, write question 1's answer and run its self-check (it must pass);
5. stop the server.

A sampler reads /proc every 0.5 s: the resident memory of each student's processes (server and
kernel, by the user's uid), the CPU time they used, and the machine's used memory. Prints the
figures, then a sizing table for instructors derived from them (the assumptions are printed too).

    python benchmarks/bench_hub.py                 # 20 students, all at once
    python benchmarks/bench_hub.py --students 8

Root only (it makes system users, removed at the end). Ports: PUMA_HUB_PORTS (default 9000-9099).
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.hub import hubctl  # noqa: E402
from tests.hub.hubctl import REPO_NAME, GitServer, Hub  # noqa: E402
from tests.hub.test_hub import ANSWER  # noqa: E402

PAGE = os.sysconf("SC_PAGE_SIZE")
TICK = os.sysconf("SC_CLK_TCK")


class Sampler(threading.Thread):
    """Peak resident memory per uid, CPU seconds per uid (summed over its processes), machine memory in use."""

    def __init__(self, uids: dict[int, str], period: float = 0.5) -> None:
        super().__init__(daemon=True)
        self.uids, self.period = uids, period
        self.peak_rss: dict[str, int] = dict.fromkeys(uids.values(), 0)
        self.cpu: dict[int, tuple[str, float]] = {}  # pid -> (user, the largest utime + stime seen)
        self.baseline = self.used()
        self.peak_used = self.baseline
        self.stop_event = threading.Event()

    @staticmethod
    def used() -> int:
        info = {}
        with open("/proc/meminfo") as f:
            for line in f:
                key, value = line.split(":", 1)
                info[key] = int(value.split()[0]) * 1024
        return info["MemTotal"] - info["MemAvailable"]

    def sample(self) -> None:
        rss: dict[str, int] = dict.fromkeys(self.uids.values(), 0)
        for entry in os.scandir("/proc"):
            if not entry.name.isdigit():
                continue
            try:
                uid = os.stat(entry.path).st_uid
                if uid not in self.uids:
                    continue
                user = self.uids[uid]
                with open(f"{entry.path}/statm") as f:
                    rss[user] += int(f.read().split()[1]) * PAGE
                with open(f"{entry.path}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                cpu = (int(fields[11]) + int(fields[12])) / TICK
                pid = int(entry.name)
                self.cpu[pid] = (user, max(cpu, self.cpu.get(pid, (user, 0.0))[1]))
            except (FileNotFoundError, ProcessLookupError, IndexError, ValueError):
                continue
        for user, value in rss.items():
            self.peak_rss[user] = max(self.peak_rss[user], value)
        self.peak_used = max(self.peak_used, self.used())

    def run(self) -> None:
        while not self.stop_event.is_set():
            self.sample()
            time.sleep(self.period)

    def cpu_seconds(self) -> dict[str, float]:
        out = dict.fromkeys(self.uids.values(), 0.0)
        for user, seconds in self.cpu.values():
            out[user] += seconds
        return out


def student(hub: Hub, git: GitServer, user: str) -> dict[str, Any]:
    row: dict[str, Any] = {"user": user}
    t0 = time.monotonic()
    try:
        row["ready"] = hub.start_server(user)
        t = time.monotonic()
        hub.pull(user, git.url)
        row["pull"] = time.monotonic() - t
        cells, may_fail = hubctl.code_cells(git.edition / "notebooks" / "01_rotations_and_transforms.ipynb")
        t = time.monotonic()
        hubctl.run_in_kernel(
            hub, user, f"{REPO_NAME}/notebooks/01_rotations_and_transforms.ipynb", cells, may_fail=may_fail
        )
        row["lecture01"] = time.monotonic() - t
        ex, _ = hubctl.code_cells(git.edition / "exercises" / "ex03_puma_fk.ipynb")
        t = time.monotonic()
        out = hubctl.run_in_kernel(
            hub,
            user,
            f"{REPO_NAME}/exercises/ex03_puma_fk.ipynb",
            [ex[0], ANSWER.format(user=user), 'check("q1", chain_fk)'],
        )
        row["selfcheck"] = time.monotonic() - t
        if "passed" not in out[-1]["outputs"] or "FAILED" in out[-1]["outputs"]:
            raise RuntimeError(f"the self-check said {out[-1]['outputs']!r}")
    except Exception as e:  # a failure is a figure here, not a crash
        row["error"] = f"{type(e).__name__}: {str(e)[:300]}"
    finally:
        try:
            hub.stop_server(user)
        except Exception:
            pass
    row["total"] = time.monotonic() - t0
    return row


def quantiles(values: list[float]) -> str:
    if not values:
        return "n/a"
    v = sorted(values)
    p95 = v[min(len(v) - 1, math.ceil(0.95 * len(v)) - 1)]
    return f"p50 {statistics.median(v):.1f} s · p95 {p95:.1f} s · max {v[-1]:.1f} s"


def sizing(mem_student: float, cpu_student: float, lecture_alone: float) -> str:
    """The instructors' table, from the measured memory (bytes) and CPU seconds per student session."""
    gib = 1024**3
    nodes = [(2, 8), (8, 32), (32, 128)]  # cores, GiB: a cloud VM's usual 4 GiB per core
    reserve = 1.5  # GiB for the OS, the hub and the proxy on a node
    burst = 30.0  # seconds a Run All may take when the whole class presses it at once
    mem_gib = mem_student / gib
    lines = [
        "| node | students by memory | students by CPU (all Run All at once, done in 30 s) | students per node |",
        "|---|---|---|---|",
    ]
    per_node = {}
    for cores, ram in nodes:
        by_mem = int((ram - reserve) / (mem_gib * 1.25))  # 25% headroom over the measured peak
        by_cpu = int(burst * cores / cpu_student) if cpu_student > 0 else by_mem
        per_node[cores] = min(by_mem, by_cpu)
        lines.append(f"| {cores} cores, {ram} GiB | {by_mem} | {by_cpu} | **{per_node[cores]}** |")
    guarantee = math.ceil(mem_gib * 1.25 * 4) / 4  # GiB, to the quarter
    lines += [
        "",
        f"Per active student: {mem_gib * 1024:.0f} MiB resident at peak (server + kernel), "
        f"{cpu_student:.1f} CPU-seconds for one session (server start, pull, lecture 01, one self-check); "
        f"lecture 01 alone took {lecture_alone:.1f} s of wall time.",
        "",
        "Zero to JupyterHub (`config.yaml`: `singleuser.memory.guarantee` / `.limit`, "
        "`singleuser.cpu.guarantee` / `.limit`):",
        "",
        f"* every class: `singleuser.memory.guarantee: {guarantee:g}G`, `limit: {2 * guarantee:g}G`; "
        f"`singleuser.cpu.guarantee: {max(0.05, cpu_student / burst):.2f}`, `limit: 1`.",
    ]
    for size in (100, 1000):
        n8 = math.ceil(size / per_node[8])
        n32 = math.ceil(size / per_node[32])
        lines.append(
            f"* {size} students active at once: {n8} nodes of 8 cores / 32 GiB, or {n32} of 32 cores / 128 GiB "
            f"(plus the hub's own small node); the user pods' memory requests add up to {size * guarantee:g} GiB."
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--students", type=int, default=20)
    ap.add_argument("--at-once", type=int, default=0, help="students driven at the same time (0: all)")
    args = ap.parse_args(argv)
    why = hubctl.why_not()
    if why:
        print(f"bench_hub: cannot start a hub here: {why}", file=sys.stderr)
        return 2
    if args.students < 1 or args.students > len(hubctl.ports()) - 4:
        print(
            f"--students: expected 1..{len(hubctl.ports()) - 4} (one port each); got {args.students}", file=sys.stderr
        )
        return 2
    names = [f"puma-bench-{i:02d}" for i in range(1, args.students + 1)]
    tmp = hubctl._open_tmp("puma-bench-")
    t = time.monotonic()
    edition = hubctl.make_edition(tmp / "edition")
    env = hubctl.single_user_env(edition)
    print(f"edition and environment ready in {time.monotonic() - t:.0f} s ({env})", flush=True)
    users = hubctl.make_users(names)
    git = hub = None
    try:
        import pwd

        git = GitServer(edition, hubctl.ports()[3])
        hub = Hub(users, env)
        for u in users:
            hub.ensure_user(u)
        sampler = Sampler({pwd.getpwnam(u).pw_uid: u for u in users})
        sampler.start()
        t = time.monotonic()
        with ThreadPoolExecutor(args.at_once or len(users)) as pool:
            rows = list(pool.map(lambda u: student(hub, git, u), users))
        wall = time.monotonic() - t
        sampler.stop_event.set()
        sampler.join()
    finally:
        if hub is not None:
            hub.stop()
            hub.cleanup()
        if git is not None:
            git.stop()
        hubctl.delete_users(users)
        shutil.rmtree(tmp, ignore_errors=True)

    ok = [r for r in rows if "error" not in r]
    failed = [r for r in rows if "error" in r]
    mib = 1024**2
    peaks = sorted(sampler.peak_rss[r["user"]] for r in ok) or [0]
    cpu = sampler.cpu_seconds()
    cpus = sorted(cpu[r["user"]] for r in ok) or [0.0]
    print(f"\n{args.students} students, {args.at_once or args.students} at once, on {os.cpu_count()} cores; "
          f"whole run {wall:.0f} s")  # fmt: skip
    print(f"time to a ready server : {quantiles([r['ready'] for r in rows if 'ready' in r])}")
    print(f"nbgitpuller first pull : {quantiles([r['pull'] for r in rows if 'pull' in r])}")
    print(f"lecture 01 (all cells) : {quantiles([r['lecture01'] for r in rows if 'lecture01' in r])}")
    print(f"exercise 3 self-check  : {quantiles([r['selfcheck'] for r in rows if 'selfcheck' in r])}")
    print(f"failures               : {len(failed)} of {len(rows)}")
    for r in failed:
        print(f"   {r['user']}: {r['error'][:200]!r}")
    print(f"peak memory per student (server + kernels): median {statistics.median(peaks) / mib:.0f} MiB, "
          f"max {peaks[-1] / mib:.0f} MiB")  # fmt: skip
    print(f"CPU per student session: median {statistics.median(cpus):.1f} s, max {cpus[-1]:.1f} s")
    print(f"machine memory in use: {sampler.baseline / mib:.0f} MiB before, peak {sampler.peak_used / mib:.0f} MiB "
          f"(+{(sampler.peak_used - sampler.baseline) / mib:.0f} MiB; other helpers' work included)")  # fmt: skip
    if ok:
        lecture_alone = min(r["lecture01"] for r in ok)
        print("\nSizing for instructors (derived from the figures above):\n")
        print(sizing(float(statistics.median(peaks)), float(statistics.median(cpus)), lecture_alone))
    return 0 if not failed else 1


if __name__ == "__main__":
    raise SystemExit(main())
