"""Small vector algebra on 3-tuples for the kernels: nothing is allocated (LLVM keeps the
tuples in registers); and the kernels' array copies."""
from __future__ import annotations

from axlebox._numba import kernel

AX, AY, AZ = 0, 1, 2            # the axes of a 3-vector's or a 3 x 3 matrix's index
ZERO = (0.0, 0.0, 0.0)
EY = (0.0, 1.0, 0.0)
ZERO6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


# the kernels' array copies: by loop, since numba's slice assignment (``dst[:] = src``) allocates a
# temporary where the two might overlap (the kernels run without reference counting,
# axlebox/_numba.py) and compiles a shape check with its error message (seconds of a cold start,
# benchmarks/README.md "The bearing core")
@kernel(inline="always")
def copy1(dst, src):
    """``dst[:] = src`` for 1-index arrays of one length."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@kernel(inline="always")
def copy2(dst, src):
    """``dst[:, :] = src`` for 2-index arrays of one shape."""
    for i in range(dst.shape[0]):
        for j in range(dst.shape[1]):
            dst[i, j] = src[i, j]


@kernel(inline="always")
def copy3(dst, src):
    """``dst[:, :, :] = src`` for 3-index arrays of one shape."""
    for i in range(dst.shape[0]):
        for j in range(dst.shape[1]):
            for k in range(dst.shape[2]):
                dst[i, j, k] = src[i, j, k]


@kernel
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@kernel
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


@kernel
def mul(k, a):
    return (k * a[0], k * a[1], k * a[2])


@kernel
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@kernel
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@kernel
def lin(ka, a, kb, b):
    """``ka a + kb b``."""
    return (ka * a[0] + kb * b[0], ka * a[1] + kb * b[1], ka * a[2] + kb * b[2])


@kernel
def get(v, o):
    """The 3-vector at ``v[o], v[o + 1], v[o + 2]``."""
    return (v[o], v[o + 1], v[o + 2])


@kernel
def put(v, o, a):
    """``v[o:o + 3] = a``."""
    v[o] = a[0]
    v[o + 1] = a[1]
    v[o + 2] = a[2]


@kernel
def acc(v, o, a):
    """``v[o:o + 3] += a``."""
    v[o] += a[0]
    v[o + 1] += a[1]
    v[o + 2] += a[2]
