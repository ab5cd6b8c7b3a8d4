"""Option groups: a set of Typer options declared once, which a command receives as one value.

`@takes("robot", ROBOT.of("urdf", "xacro_arg"))` puts the group's options in the command's
signature in place of its `robot` parameter (so --help lists them there) and calls the command
with `robot=` the group's value, built from them."""

from __future__ import annotations

import functools
import inspect
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class OptionGroup:
    """Typer parameters, name -> (annotation, default), and `build`, which turns their values
    (as keyword arguments) into the group's value."""

    params: dict[str, tuple[Any, Any]]
    build: Callable[..., Any]

    def of(self, *names: str, **annotations: Any) -> OptionGroup:
        """The group with only `names` (in that order), `annotations` replacing the declared ones
        (a command's own help text or default: `name=(annotation, default)`)."""
        params = {name: annotations[name] if name in annotations else self.params[name] for name in names}
        return OptionGroup(params, self.build)


def takes(name: str, group: OptionGroup) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Give the decorated command's parameter `name` the value of `group`, whose options take its
    place in the command's signature."""

    def decorate(command: Callable[..., Any]) -> Callable[..., Any]:
        hints = typing.get_type_hints(command, include_extras=True)
        own = [
            p.replace(annotation=hints.get(p.name, p.annotation), kind=inspect.Parameter.KEYWORD_ONLY)
            for p in inspect.signature(command).parameters.values()
        ]
        at = [p.name for p in own].index(name)
        added = [
            inspect.Parameter(option, inspect.Parameter.KEYWORD_ONLY, annotation=annotation, default=default)
            for option, (annotation, default) in group.params.items()
        ]
        params = [*own[:at], *added, *own[at + 1 :]]

        @functools.wraps(command)
        def wrapper(**kwargs: Any) -> Any:
            value = group.build(**{option: kwargs.pop(option) for option in group.params})
            return command(**kwargs, **{name: value})

        del wrapper.__wrapped__  # Typer reads the signature below, not the command's
        wrapper.__signature__ = inspect.Signature(params)  # type: ignore[attr-defined]
        wrapper.__annotations__ = {p.name: p.annotation for p in params}
        return wrapper

    return decorate
