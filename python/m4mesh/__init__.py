"""m4mesh's Python side: rate–distortion plots of `m4mesh rd` sweeps (m4mesh.plot)."""
