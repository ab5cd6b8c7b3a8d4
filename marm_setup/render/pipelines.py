"""What config/moveit.yaml (ros2) writes for each planning pipeline: its planner plugin, request
and response adapters and parameters as its distro reads them (moveit_params/pipeline_params.py: names,
types, marm-setup's defaults overlaid with the setup's `pipeline_parameters`), and the pipelines'
capabilities, which Humble's move_group reads only from the top-level `capabilities`."""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.moveit_params import PIPELINES, PipelineParameterValue, effective_parameters
from marm_setup.setup import SetupModel

ADAPTER_KEYS = ("request_adapters", "response_adapters")


@dataclass(frozen=True, slots=True)
class ParamNode:
    """A parameter line of a pipeline's namespace, or a sub-namespace (`totg`) of `children`."""

    name: str
    value: PipelineParameterValue | None = None
    children: tuple[ParamNode, ...] = ()


@dataclass(frozen=True, slots=True)
class PipelineInfo:
    """One pipeline as moveit.yaml writes it (`key`: the setup's name, `namespace`: MoveIt's)."""

    key: str
    namespace: str
    plugin: str
    request_adapters: tuple[str, ...]
    response_adapters: tuple[str, ...]
    parameters: tuple[ParamNode, ...]
    capabilities: str = ""  # Humble: move_group's top-level capabilities take them


def pipeline_infos(model: SetupModel) -> list[PipelineInfo]:
    """Every pipeline of the setup, in its order, for the setup's ROS 2 distro."""
    given = dict(model.pipeline_parameters)
    out = []
    for key in model.planning_pipelines:
        pipeline = PIPELINES[key]
        values = dict(effective_parameters(key, model.distro, given.get(key, ())))
        adapters = {k: tuple(values.pop(k, ())) for k in ADAPTER_KEYS}  # type: ignore[arg-type]
        capabilities = str(values.pop("capabilities", "")) if model.row.top_level_capabilities else ""
        out.append(
            PipelineInfo(
                key,
                pipeline.namespace,
                pipeline.plugin_ros2,
                adapters["request_adapters"],
                adapters["response_adapters"],
                nest(tuple(values.items())),
                capabilities,
            )
        )
    return out


def top_level_capabilities(infos: list[PipelineInfo]) -> str:
    """The capabilities of every pipeline (Humble), space-separated, each once."""
    names = [c for info in infos for c in info.capabilities.split()]
    return " ".join(dict.fromkeys(names))


def nest(values: tuple[tuple[str, PipelineParameterValue], ...]) -> tuple[ParamNode, ...]:
    """Dotted names (`totg.path_tolerance`) as a sub-namespace, in the order first seen."""
    out: list[ParamNode] = []
    for name, value in values:
        head, dot, rest = name.partition(".")
        if not dot:
            out.append(ParamNode(name, value))
            continue
        index = next((i for i, n in enumerate(out) if n.name == head and n.children), None)
        child = nest(((rest, value),))
        if index is None:
            out.append(ParamNode(head, children=child))
        else:
            out[index] = ParamNode(head, children=out[index].children + child)
    return tuple(out)
