"""m4mesh from Python: encode and decode 3D mesh sequences with every codec,
decode progressively, measure, read 2D streams, run the conformance suite
(numpy arrays in and out), and plot rate–distortion sweeps (m4mesh.plot).

    import numpy as np, m4mesh
    stream = m4mesh.encode(frames, faces, codec="lcc", target_kg=0.1)  # frames: float32[F, V, 3]
    decoded, faces = m4mesh.decode(stream)
    print(m4mesh.metrics(frames, decoded, faces)["kg_error"])

Every failure raises m4mesh.Error, with the element, frame and bit offset.
"""

from ._errors import Error

__all__ = ["Error", "codecs", "conform", "decode", "encode", "frames", "metrics", "progressive", "read_2d"]


def __dir__():
    return sorted(set(__all__) | {"plot"})


def __getattr__(name):
    # The native part loads on first use: m4mesh.plot needs only matplotlib.
    if name in __all__:
        from . import _native

        return getattr(_native, name)
    raise AttributeError(f"module 'm4mesh' has no attribute {name!r}")
