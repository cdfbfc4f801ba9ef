"""No leak: 1,000 reads of a small NIfTI grow the resident set by less than 5 MiB after the
first 100 (which warm the allocator and the libraries' caches)."""
import os

import mvw


def _rss_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_reads_do_not_leak(data):
    path = data / "nibabel" / "anatomical.nii"
    for _ in range(100):
        mvw.read(path).array.sum()
    before = _rss_bytes()
    for _ in range(900):
        mvw.read(path).array.sum()
    grown = _rss_bytes() - before
    assert grown < 5 * 1024 * 1024, f"1,000 reads grew the resident set by {grown} bytes"
