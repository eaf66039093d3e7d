"""Typed errors. Every message names the offending value and the rule it breaks."""


class SimOrigamiError(Exception):
    """Base class of every error raised on purpose by sim_origami."""


class ParameterError(SimOrigamiError, ValueError):
    """An unknown parameter, or a value that breaks a rule of the geometry."""


class DomainError(SimOrigamiError, ValueError):
    """An input angle outside the validity domain of the requested branch."""


class AssemblyError(SimOrigamiError):
    """A linkage whose loop cannot be closed; the message names the closure residual."""


class ConvergenceError(SimOrigamiError):
    """The numeric loop-closure solve did not converge."""


class SimulationError(SimOrigamiError):
    """
    MuJoCo reported a warning (e.g. bad qacc) or the run diverged. `verdicts`: the checks a validation had made when
    it stopped, with those that need no MuJoCo (`validation.validate` sets them), which the failed run's report keeps.
    """

    verdicts: tuple = ()


class RenderError(SimOrigamiError):
    """No working headless OpenGL backend."""
