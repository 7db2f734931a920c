"""Python side of dynamic-contact: readers of the files a run writes
(doc/output.md) and standard plots.

Modules:
    dynamic_contact.output    time_series.csv, contact_NNNNN.csv, run_status,
                              the output directory as a whole (Run)
    dynamic_contact.vtu       the VTU/PVTU records and .pvd collections
                              (numpy only, no VTK)
    dynamic_contact.prm       the entries of a parameter file
    dynamic_contact.plotting  the plots of scripts/plot-run (matplotlib)

Needs numpy; plotting needs matplotlib. Install with
`pip install -e python/` (or use the scripts of the repository, which find
the package without installing it: python/README.md).
"""

from .output import (Run, Table, contact_files, is_completed, read_contact,
                     read_run_status, read_table, read_time_series)
from .prm import read_prm, test_overrides
from .vtu import UnstructuredGrid, read_pvd, read_vtu

__all__ = ["Run", "Table", "UnstructuredGrid", "contact_files",
           "is_completed", "read_contact", "read_prm", "read_pvd",
           "read_run_status", "read_table", "read_time_series", "read_vtu",
           "test_overrides"]
__version__ = "0.1.0"
