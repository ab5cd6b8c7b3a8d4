"""The files that say where a package's robot is and who made it: the Setup Assistant's
`.setup_assistant`, marm-setup's `marm_setup.yaml` (read leniently here: validate reads broken
ones too; `setup.yaml_io` is the strict reader render uses) and `package.xml`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from marm_setup.errors import InputError
from marm_setup.package.where import Located
from marm_setup.ros import DISTROS, TARGETS, Distro, Target

if TYPE_CHECKING:
    from marm_setup.setup import SetupModel

# marm_setup.yaml keys no rendered file holds: a port keeps them from the source's file.
KEPT_KEYS = ("collision", "default_acceleration", "driver")


def _mapping(value: Any) -> dict:
    return value if isinstance(value, dict) else {}


@dataclass(frozen=True, slots=True)
class SetupAssistantFile:
    """`.setup_assistant` (MoveIt 1 `URDF` / `SRDF` / `CONFIG`, MoveIt 2 lower-case keys and
    `package_settings`); `readable` false when it is not a YAML mapping."""

    readable: bool
    urdf_package: str | None = None
    urdf_path: str | None = None
    urdf_xacro_args: tuple[tuple[str, str], ...] = ()
    srdf_path: str | None = None
    srdf_key: str = "SRDF"  # as written (SRDF or srdf), for findings
    author_name: str | None = None
    author_email: str | None = None
    author_key: str = ""  # CONFIG, config or package_settings


def read_setup_assistant(doc: Located | None) -> SetupAssistantFile:
    config = _mapping(_mapping(doc.data if doc is not None else None).get("moveit_setup_assistant_config"))
    if doc is None or not config:
        return SetupAssistantFile(doc is not None and isinstance(doc.data, dict))
    urdf = _mapping(config.get("URDF", config.get("urdf")))
    srdf = _mapping(config.get("SRDF", config.get("srdf")))
    author_key = next(
        (k for k in ("CONFIG", "config", "package_settings") if isinstance(config.get(k), dict)), ""
    )
    author = _mapping(config.get(author_key))
    args = str(urdf.get("xacro_args") or "").split()
    return SetupAssistantFile(
        True,
        _package(urdf.get("package")),
        _text(urdf.get("relative_path")),
        xacro_pairs(args),
        _text(srdf.get("relative_path")) if isinstance(srdf.get("relative_path"), str) else None,
        "SRDF" if "SRDF" in config else "srdf",
        _text(author.get("author_name")),
        _text(author.get("author_email")),
        author_key,
    )


def _text(value: Any) -> str | None:
    return str(value) if value not in (None, "") else None


def _package(value: Any) -> str | None:
    """URDF.package as the MoveIt 1 Setup Assistant reads it: trimmed, and empty or `""` names
    no package (relative_path is then the file itself; moveit/moveit
    moveit_setup_assistant/src/tools/moveit_config_data.cpp l.1727-1734)."""
    text = _text(value)
    return None if text is None or text.strip() in ("", '""') else text.strip()


def xacro_pairs(value: Any) -> tuple[tuple[str, str], ...]:
    """xacro args given as a mapping, a list of `NAME:=VALUE` or a list of pairs (sorted)."""
    if isinstance(value, dict):
        return tuple(sorted((str(k), str(v)) for k, v in value.items()))
    out = []
    for item in value or ():
        if isinstance(item, str) and ":=" in item:
            name, _, val = item.partition(":=")
            out.append((name, val))
        elif isinstance(item, list | tuple) and len(item) == 2:
            out.append((str(item[0]), str(item[1])))
    return tuple(sorted(out))


@dataclass(frozen=True, slots=True)
class MarmSetupFile:
    """What discovery needs of a `marm_setup.yaml`, read leniently (a broken key reads as
    absent); `readable` false when it is not a YAML mapping."""

    readable: bool
    robot_name: str | None = None
    target: Target | None = None
    ros_distro: Distro | None = None
    urdf: str | None = None
    xacro_args: tuple[tuple[str, str], ...] = ()
    package_paths: tuple[str, ...] = ()
    collision_seed: int | None = None
    collision_trials: int | None = None
    author: tuple[str, str] | None = None
    kept_keys: tuple[str, ...] = ()  # which of KEPT_KEYS the file has
    kept: SetupModel | None = None  # those keys, read strictly (setup.yaml_io)
    kept_error: InputError | None = None  # why they could not be read
    proofs: RecordedProofs | None = None  # what `collision` records of its matrix's proofs


Pair = tuple[str, str]


@dataclass(frozen=True, slots=True)
class RecordedProofs:
    """What a marm_setup.yaml records of its matrix's proofs (`collision.prove` on or
    exhaustive): its Never pairs and its unproved ones (with the share of the joint range
    proved) as written, and the proof key that ties them to one robot: claims, for information
    (validate trusts no proof a package records)."""

    prove: str
    never: tuple[Pair, ...]
    unproved: tuple[tuple[Pair, float], ...]
    key: str | None


def read_proofs(collision: dict) -> RecordedProofs | None:
    """The proofs a `collision` mapping records; None when it records none or a list is
    malformed (then nothing is trusted)."""
    prove = collision.get("prove")
    if prove not in ("on", "exhaustive"):
        return None
    disabled = _items(collision.get("disabled"))
    unproved = _items(collision.get("unproved"))
    if disabled is None or unproved is None:
        return None
    never = [_pair(i) for i in disabled if i.get("reason") == "Never"]
    shares = [(_pair(i), _share(i.get("proved_fraction"))) for i in unproved]
    if any(p is None for p in never) or any(p is None for p, _ in shares):
        return None
    key = collision.get("proof_key")
    return RecordedProofs(
        str(prove),
        tuple(p for p in never if p is not None),
        tuple((p, s) for p, s in shares if p is not None),
        key if isinstance(key, str) else None,
    )


def _items(value: Any) -> list[dict] | None:
    """A list of mappings ([] when absent); None when it is something else."""
    if value is None:
        return []
    return value if isinstance(value, list) and all(isinstance(i, dict) for i in value) else None


def _pair(item: dict) -> Pair | None:
    a, b = item.get("link1"), item.get("link2")
    return (a, b) if isinstance(a, str) and isinstance(b, str) else None


def _share(value: Any) -> float:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else 0.0


def read_marm_setup(doc: Located | None, shown: str = "marm_setup.yaml") -> MarmSetupFile:
    data = doc.data if doc is not None else None
    if not isinstance(data, dict):
        return MarmSetupFile(False)
    robot = _mapping(data.get("robot"))
    collision = _mapping(data.get("collision"))
    paths = robot.get("package_paths")
    author = _mapping(data.get("author"))
    kept_keys = tuple(k for k in KEPT_KEYS if k in data)
    kept, kept_error = _kept(data, kept_keys, shown)
    return MarmSetupFile(
        True,
        _text(data.get("robot_name")) if data.get("robot_name") else None,
        Target(data["target"]) if data.get("target") in TARGETS else None,
        str(data["ros_distro"]) if data.get("ros_distro") in DISTROS else None,
        robot.get("urdf") if isinstance(robot.get("urdf"), str) else None,
        xacro_pairs(robot.get("xacro_args")),
        tuple(p for p in paths if isinstance(p, str)) if isinstance(paths, list) else (),
        _count(collision.get("seed")),
        _count(collision.get("trials")),
        (str(author["name"]), str(author["email"])) if author.get("name") and author.get("email") else None,
        kept_keys,
        kept,
        kept_error,
        read_proofs(collision),
    )


def _kept(data: dict, keys: tuple[str, ...], shown: str) -> tuple[SetupModel | None, InputError | None]:
    from marm_setup.setup import setup_from_dict

    try:
        given = {"package_name": "-", "robot_name": "-", "robot": {"urdf": "-"}, **{k: data[k] for k in keys}}
        return setup_from_dict(given, shown), None
    except InputError as exc:
        return None, exc


def _integer(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def _count(value: Any) -> int | None:
    """A seed or trial count: a non-negative integer (a negative seed is one numpy's SeedSequence
    refuses: read as absent, as any broken key is here; the strict reader names it)."""
    found = _integer(value)
    return found if found is not None and found >= 0 else None


@dataclass(frozen=True, slots=True)
class PackageXml:
    """package.xml as the port and discovery read it (catkin_pkg validates it in validate)."""

    file: str
    text: str
    parsed: bool = False  # false when the XML does not parse
    name: str | None = None
    maintainers: tuple[tuple[str, str], ...] = ()
    licenses: tuple[str, ...] = ()
    metadata: tuple[tuple[str, str], ...] = ()  # (tag, text) of version, description, url, author
    dependencies: tuple[str, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        """The package's own name and those it depends on (what a launch file may $(find))."""
        return tuple(n for n in (self.name, *self.dependencies) if n)

    @property
    def build_type(self) -> str | None:
        """ament (ROS 2) or catkin (ROS 1), from the text as discovery always read it."""
        if "ament_cmake" in self.text or "ament_python" in self.text:
            return "ament"
        return "catkin" if "catkin" in self.text else None


def read_package_xml(file: str, text: str) -> PackageXml:
    from lxml import etree

    try:
        root = etree.fromstring(text.encode("utf-8"))
    except (etree.XMLSyntaxError, ValueError):
        return PackageXml(file, text)
    people = tuple(
        ((e.text or "").strip(), e.get("email", "").strip())
        for e in root.iterchildren("maintainer")
        if (e.text or "").strip() and e.get("email")
    )
    name = root.findtext("name")
    metadata = tuple(
        (e.tag, _element_text(e))
        for e in root.iterchildren()
        if e.tag in ("version", "description", "url", "author")
    )
    deps = tuple(sorted({(e.text or "").strip() for e in root if str(e.tag).endswith("depend")}))
    licenses = tuple((e.text or "").strip() for e in root.iterchildren("license"))
    return PackageXml(file, text, True, name.strip() if name else None, people, licenses, metadata, deps)


def _element_text(elem: Any) -> str:
    return " ".join("".join(elem.itertext()).split())
