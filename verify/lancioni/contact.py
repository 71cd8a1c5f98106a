"""The frictional unilateral contact of Lancioni et al.'s models is the shared contact-mechanics
module of the simulation layer, :mod:`landau.verify.hybrid.contact`; this name is kept for
existing imports."""

from landau.verify.hybrid.contact import (
                                          ContactMechanics,
                                          ContactModel,
                                          ContactSolution,
                                          ImpactResult,
                                          PainleveError,
                                          PointMassOnPlane,
                                          Section,
                                          contact_problem,
                                          default_options,
                                          poisson_impact,
                                          slip_forces,
                                          stick_forces,
)

__all__ = ["ContactMechanics", "ContactModel", "ContactSolution", "ImpactResult", "PainleveError",
           "PointMassOnPlane", "Section", "contact_problem", "default_options", "poisson_impact", "slip_forces",
           "stick_forces"]
