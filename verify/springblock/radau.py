"""The compiled Radau IIA (order 5) the spring–block runs on lives in the simulation layer,
:mod:`landau.verify.hybrid.radau`; this name is kept for existing imports."""

from landau.verify.hybrid.radau import (A_RADAU, C_NODES, E_ERR, FUN_T, JAC_T, MU_REAL, SIG, SIG_JAC, STATUS,
                                        VINV, radau_core)

__all__ = ["A_RADAU", "C_NODES", "E_ERR", "FUN_T", "JAC_T", "MU_REAL", "SIG", "SIG_JAC", "STATUS", "VINV",
           "radau_core"]
