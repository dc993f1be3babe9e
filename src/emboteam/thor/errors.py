"""Typed errors of the AI2-THOR environment."""

from __future__ import annotations

from emboteam.errors import EXIT_BAD_INPUT, EXIT_SERVICE, EmboTeamError


class ThorUnavailableError(EmboTeamError):
    """No AI2-THOR build can be started here: the package is missing, there is neither an X
    display with GLX nor a Vulkan driver, the build is neither cached nor downloadable, or
    the Unity process did not answer in time. A service the command needs: exit 3."""

    exit_code = EXIT_SERVICE


class ThorSetupError(EmboTeamError):
    """A task's initial state that AI2-THOR cannot be put into (e.g. an object's
    temperature, which no AI2-THOR action sets directly)."""

    exit_code = EXIT_BAD_INPUT


class ThorTeamError(EmboTeamError):
    """A team AI2-THOR cannot host: more robots join than agents were started (AI2-THOR
    fixes ``agentCount`` when the scene is initialised)."""

    exit_code = EXIT_BAD_INPUT
