"""Kept for old imports: the VTU reader is dynamic_contact.vtu now
(python/dynamic_contact/vtu.py); `from vtu_reader import read_vtu` still
works for scripts in this directory."""

from dynamic_contact.vtu import UnstructuredGrid, read_pvd, read_vtu  # noqa: F401
