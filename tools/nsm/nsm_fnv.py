"""FNV-1a 64 (core/hash.h's Fnv1a) of a byte string: the trailing checksum of .nsmf and .nsmw.

The hash is sequential, so numpy cannot vectorize it; a data set's frames are megabytes each,
so a small C loop is compiled once with the system's `cc` into ~/.cache/shadowlab_nsm and
called through ctypes. Without a compiler the pure-Python loop gives the same value, slowly.
"""
import ctypes
import hashlib
import os
import subprocess
import tempfile

OFFSET = 0xCBF29CE484222325
PRIME = 0x100000001B3
MASK = (1 << 64) - 1

_C_SOURCE = r"""
#include <stdint.h>
#include <stddef.h>
uint64_t fnv1a64(const unsigned char* p, size_t n, uint64_t h) {
  for (size_t i = 0; i < n; ++i) { h ^= p[i]; h *= 0x100000001b3ull; }
  return h;
}
"""
_lib = None
_tried = False


def fnv1a64_python(data, h=OFFSET):
    for b in bytes(data):
        h = ((h ^ b) * PRIME) & MASK
    return h


def _load_c():
    global _lib, _tried
    if _tried:
        return _lib
    _tried = True
    try:
        tag = hashlib.sha1(_C_SOURCE.encode()).hexdigest()[:12]
        cache = os.path.join(os.path.expanduser("~"), ".cache", "shadowlab_nsm")
        os.makedirs(cache, exist_ok=True)
        so = os.path.join(cache, f"fnv1a_{tag}.so")
        if not os.path.exists(so):
            with tempfile.TemporaryDirectory() as tmp:
                src = os.path.join(tmp, "fnv.c")
                with open(src, "w") as f:
                    f.write(_C_SOURCE)
                out = os.path.join(tmp, "fnv.so")
                subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-o", out, src], check=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                os.replace(out, so)  # atomic: concurrent runs never load a half-written file
        lib = ctypes.CDLL(so)
        lib.fnv1a64.restype = ctypes.c_uint64
        lib.fnv1a64.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint64]
        _lib = lib
    except (OSError, subprocess.CalledProcessError):
        _lib = None
    return _lib


def fnv1a64(data, h=OFFSET):
    """FNV-1a 64 of `data` (bytes-like), continuing from state h."""
    data = bytes(data) if not isinstance(data, bytes) else data
    lib = _load_c()
    if lib is None:
        return fnv1a64_python(data, h)
    return int(lib.fnv1a64(data, len(data), h))
