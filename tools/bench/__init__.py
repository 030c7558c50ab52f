"""Benchmarks against POV-Ray, Embree and manifold3d, and profiles."""
