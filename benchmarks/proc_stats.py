"""What the benchmarks read of the machine (Linux ``/proc``): memory and CPU time.

Shared by ``assess_bench.py`` and ``campaign_bench.py`` (run as scripts from this folder,
which Python puts first on the path). Not part of the package or the test suite.
"""

from __future__ import annotations

import os

__all__ = ["busy_cpu_s", "own_rss", "tree_rss"]


def tree_rss(pid: int) -> int:
    """Resident memory [B] of a process and all its descendants (Linux /proc)."""
    children: dict[int, list[int]] = {}
    rss = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            ppid, pages = int(fields[1]), int(fields[21])
        except (OSError, IndexError, ValueError):
            continue  # the process ended meanwhile
        children.setdefault(ppid, []).append(int(entry))
        rss[int(entry)] = pages * os.sysconf("SC_PAGE_SIZE")
    total, stack = 0, [pid]
    while stack:
        p = stack.pop()
        total += rss.get(p, 0)
        stack.extend(children.get(p, []))
    return total


def own_rss() -> int:
    """Resident memory [B] of this process now (Linux /proc/self/statm)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def busy_cpu_s() -> float:
    """Non-idle CPU time of the whole machine since boot [s] (Linux /proc/stat)."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:]]
    idle = fields[3] + fields[4]  # idle + iowait
    return (sum(fields[:8]) - idle) / os.sysconf("SC_CLK_TCK")
