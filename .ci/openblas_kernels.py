"""Print two OpenBLAS kernels this CPU can run, for CI's two unit-test passes.

Results must not depend on the BLAS kernel (README, "Results must not depend on the
machine"), so `.ci/run` runs the unit tests once under each kernel printed here. The
first is a modern kernel the CPU supports, the second an old baseline one, so the two
passes take different code paths in OpenBLAS (different blocking, FMA or not).

With ``--in-use`` it prints instead the kernel numpy's OpenBLAS actually runs (read through
threadpoolctl), so `.ci/run` can check that the two passes really ran different kernels
(OpenBLAS reports some kernels under another name: Prescott runs as "Katmai").
"""

from __future__ import annotations

import platform
import sys
from pathlib import Path


def cpu_flags() -> set[str]:
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    for line in text.splitlines():
        if line.startswith(("flags", "Features")):
            return set(line.split(":", 1)[1].split())
    return set()


def kernels() -> tuple[str, str]:
    machine = platform.machine().lower()
    flags = cpu_flags()
    if machine in ("x86_64", "amd64"):
        modern = "Haswell" if "avx2" in flags else "Sandybridge"
        if modern == "Sandybridge" and "avx" not in flags:
            modern = "Nehalem"
        return modern, "Prescott"
    if machine in ("aarch64", "arm64"):
        return "NEOVERSEN1", "ARMV8"
    return "", ""  # unknown platform: let OpenBLAS choose (both passes then use the same kernel)


def running_kernel() -> str:
    import numpy  # noqa: F401  (loads OpenBLAS)
    from threadpoolctl import threadpool_info

    archs = [str(i.get("architecture", "")) for i in threadpool_info() if i.get("internal_api") == "openblas"]
    return archs[0] if archs else ""


if __name__ == "__main__":
    if sys.argv[1:] == ["--in-use"]:
        print(running_kernel() or "unknown")
        sys.exit(0)
    print(*kernels())
