"""Benchmark families for bench/run: problems with known answers, mesh-refined.

A family module defines
  NAME, DESCRIPTION
  SIZES = {'quick': [...], 'full': [...]}        target DOF counts for superjoin
  CCX_SIZES = {'quick': [...], 'full': [...]}    target DOF counts for CalculiX ([] if none)
  superjoin_deck(dofs) -> (deck text, probe)     probe = (substructure, node, dof index 0..5)
  ccx_deck(dofs) -> (inp text, node id, dof index 0..2)
  exact(dofs) -> exact value of the probe for the model generated at that size
and is listed in FAMILIES below.  Optional: VARIANTS = ['S4', 'S3'] runs superjoin
once per variant, superjoin_deck(dofs, variant), CSV program 'superjoin-S4' etc.
(the plate family).
"""
from . import truss, beam, plate

FAMILIES = {m.NAME: m for m in (truss, beam, plate)}
