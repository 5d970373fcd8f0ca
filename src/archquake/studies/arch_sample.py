r"""The irregular sample of a study: arches drawn around a nominal arch [paper, eq. (1)], their
seeds, the one rule for an arch that cannot be analysed, and the nominal arch's model.

Both fragility studies (:mod:`archquake.studies.fragility` under pulses,
:mod:`archquake.studies.record_fragility` under records) and the paper's reproduction draw their
irregular arches here, so that they analyse the same arches and treat them alike.

Drawing and seeding
-------------------
Arch :math:`i` of the sample :class:`ArchSample` ``(nominal, epsilon, seed)`` is
:func:`archquake.geometry.irregular_arch` (eq. (1) of [1]_) drawn with its own generator, seeded
by child :math:`i` of ``numpy.random.SeedSequence(seed)``, i.e. ``SeedSequence(seed,
spawn_key=(i,))`` (:func:`archquake.execution.item_seed_sequence`). It depends on ``seed`` and
:math:`i` only, not on the size of the sample, the chunks, the workers or the order in which they
run: arch :math:`i` of a study is arch :math:`i` of
``irregular_sample(nominal, epsilon, n, seed)`` and of
:func:`archquake.limit_analysis.limit_sample` with the same seed, for any :math:`n > i`, and the
report's arches RA-1 and RA-2 are arches 0 and 1.

Arches that cannot be analysed
------------------------------
With a large :math:`\varepsilon` (or a thin nominal arch) a drawn arch may not be an arch, may
not stand under its own weight, or may have a collapse mechanism the four-link model does not
describe (:data:`EXCLUSIONS`). Such an arch is **excluded**, not allowed to stop the study: it is
not analysed, its rows carry ``status`` :data:`STATUS_EXCLUDED` and the reason in the column
``excluded``, it is named by index and seed in the study's result and summary
(:func:`exclusion_summary`), and it is left out of :math:`h`, so the probability of failure is
that of the drawn arches that stand (conditional on the draw being an analysable arch). This is
what an engineer running a long study expects: the study finishes and says what it left out and
why, rather than stopping at arch 3712 of 10000. A study whose *every* arch is excluded has
nothing to estimate: that is an error (:func:`check_analysed`).

Not excluded:

- an arch that never collapses (a line of thrust fits inside it for every load multiplier, in
  both directions): it is analysed, and stays at rest under every motion (:math:`\tilde k =
  \infty`), a survival;
- any other error (an integrator failure, a bug): it is no property of the arch, so it stops the
  study with a :class:`~archquake.errors.StudyError` naming the arch (:func:`study_error`);
- the nominal arch: a study checks it before it starts (:func:`check_nominal`), since every
  result is compared with it.

The limit-analysis sample of the pulse study (:meth:`ArchSample.load_multipliers`) applies the
same rule to what its analysis needs: an arch that is not an arch or cannot stand is excluded
(:math:`\tilde k` = nan), one that never collapses has :math:`\tilde k = \infty`.

Bridges
-------
A bridge of several spans of one arch (a :class:`~archquake.geometry.StructureSpec` with
``spans``) is sampled by :class:`BridgeSample`: member :math:`i` puts one irregular arch on every
span, drawn one after the other from the same child :math:`i` of the seed
(:meth:`~archquake.geometry.StructureSpec.member`), and is analysed by the rigid blocks alone. A
member whose piers cannot seat its draws is excluded as ``"not seated"``; its standing and its
:math:`\tilde k` come from the assembly's limit analysis. The settings of both studies draw
either sample through :class:`StudySample`.

The nominal arch
----------------
A study stores its nominal arch as data (:meth:`archquake.geometry.CircularArch.to_dict`; its
canonical JSON text, :func:`nominal_json`, identifies it) and every worker needs its model (for
the restitution model ``"nominal"``, and as the record study's reference arch):
:func:`nominal_model` builds it once per process and (arch, restitution, model).

References
----------
.. [1] The paper, Sect. 2, eq. (1), and Sect. 5.3.3 (h = 40 arches for the fragility curves,
   s = 1000 for the distribution of the load multiplier).
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..checks import check_integer, json_dumps
from ..geometry import BlockArch, arch_from_dict, check_epsilon, irregular_arch
from ..models import ModelSpec, model_spec

STATUS_EXCLUDED = -2
"""``status`` of the rows of an excluded arch in a study table (not analysed; see
:data:`EXCLUSIONS`); -1 is :attr:`archquake.status.Status.UNDECIDED`, an analysis the
rigid-block model could not decide."""

EXCLUSIONS = {
    "not an arch": "the draw of eq. (1) separates neighbouring voussoirs (their radial "
                   "extents no longer overlap) or makes a voussoir thicker than its diameter",
    "cannot stand": "no line of thrust fits inside the arch under its own weight: it falls "
                    "without any ground motion, so it has no activation threshold",
    "not analysable": "the arch stands but its collapse mechanism is not the four-link "
                      "mechanism of the dynamics (e.g. a joint that opens over its whole depth, "
                      "or no mechanism in one direction)",
    "not seated": "the irregular arches drawn for the spans of a bridge have springings its "
                  "piers cannot seat (thicker end voussoirs need wider seats): that bridge "
                  "cannot be built",
}
"""Why an arch of a sample is excluded (not analysed), by the name a study records in its
column ``excluded`` ("" for an analysed arch), in the order summaries list them. Excluded
arches are counted and named (index, seed) in a study's summary and left out of h: the
probability of failure is that of the arches that stand. An arch that cannot stand would fail
at every amplitude; counting those as failures instead would raise P_F by at most (their
number) / h everywhere."""

NEVER_COLLAPSES = (math.inf, math.inf)
"""``(k_l, k_r)`` of an arch that never collapses [-]: no load multiplier sets it in motion."""


@dataclass(frozen=True)
class SampledArch:
    """One arch of a sample as a study sees it: the model to analyse, or why there is none.

    Attributes
    ----------
    index : int
        The arch's index in the sample.
    arch : BlockArch or None
        The drawn arch (None if the draw is not an arch).
    model : StructuralModel or None
        Its model (:func:`archquake.models.model_for`); None if it is excluded or never
        collapses.
    excluded : str
        "" for an analysed arch, else the reason (a key of :data:`EXCLUSIONS`).
    """

    index: int
    arch: BlockArch | None
    model: Any
    excluded: str = ""

    @property
    def analysed(self) -> bool:
        """Whether the arch is analysed (not excluded)."""
        return not self.excluded

    @property
    def never_collapses(self) -> bool:
        """Whether the arch is analysed without a model: it stays at rest under every motion."""
        return self.analysed and self.model is None

    @property
    def load_multipliers(self) -> tuple[float, float]:
        """``(k_l, k_r)`` [-]: the model's; inf for an arch that never collapses, nan for an
        excluded one."""
        if self.model is not None:
            k_l, k_r = self.model.load_multipliers
            return float(k_l), float(k_r)
        return NEVER_COLLAPSES if self.analysed else (math.nan, math.nan)


@dataclass(frozen=True, eq=False)
class ArchSample:
    r"""Irregular arches drawn around a nominal arch [paper, eq. (1)], arch :math:`i` from
    ``SeedSequence(seed, spawn_key=(i,))`` (module docstring).

    Parameters
    ----------
    nominal : CircularArch or ShapedArch
        The nominal arch: any arch with a centreline to perturb.
    epsilon : float
        :math:`\varepsilon` of eq. (1) [-], in [0, 1); 0 draws the nominal arch itself.
    seed : int
        Root seed, >= 0.

    Raises
    ------
    ValueError
        For an arch without a centreline, an epsilon outside [0, 1) or a seed that is not an
        integer >= 0 (the message names the parameter).

    Examples
    --------
    >>> from archquake import oppenheim
    >>> from archquake.geometry import irregular_sample
    >>> sample = ArchSample(oppenheim(), 0.10, seed=7)
    >>> bool(np.array_equal(sample.arch(2).thicknesses,
    ...                     irregular_sample(oppenheim(), 0.10, 3, 7)[2].thicknesses))
    True
    """

    nominal: BlockArch
    epsilon: float
    seed: int

    def __post_init__(self) -> None:
        if not isinstance(self.nominal, BlockArch):
            raise ValueError(f"nominal must be an arch (CircularArch or ShapedArch), got "
                             f"{type(self.nominal).__name__}")
        if not hasattr(self.nominal, "perturbed"):
            raise ValueError(f"nominal must be an arch with a centreline to draw irregular "
                             f"arches around (CircularArch or ShapedArch), got "
                             f"{type(self.nominal).__name__}")
        object.__setattr__(self, "epsilon", check_epsilon(self.epsilon))
        object.__setattr__(self, "seed", check_integer("seed", self.seed, minimum=0))

    def generator(self, index: int) -> np.random.Generator:
        """The random generator of arch ``index``: ``default_rng(SeedSequence(seed,
        spawn_key=(index,)))``.

        Parameters
        ----------
        index : int
            Arch index, >= 0.

        Returns
        -------
        numpy.random.Generator
        """
        from ..execution import item_seed_sequence

        return np.random.default_rng(item_seed_sequence(self.seed, int(index)))

    def arch(self, index: int) -> BlockArch:
        """Arch ``index`` of the sample (:func:`archquake.geometry.irregular_arch`).

        Parameters
        ----------
        index : int
            Arch index, >= 0.

        Returns
        -------
        CircularArch or ShapedArch

        Raises
        ------
        ValueError
            If the draw is not an arch (:data:`EXCLUSIONS`, ``"not an arch"``).
        """
        return irregular_arch(self.nominal, self.epsilon, self.generator(index))

    def arches(self, indices) -> list[BlockArch]:
        """Arches of the sample.

        Parameters
        ----------
        indices : int or iterable of int
            A count ``n`` (arches ``0 .. n-1``) or the indices.

        Returns
        -------
        list of CircularArch or ShapedArch

        Raises
        ------
        ValueError
            If a draw is not an arch.
        """
        if isinstance(indices, int | np.integer):
            indices = range(int(indices))
        return [self.arch(i) for i in indices]

    def draw(self, index: int) -> tuple[BlockArch | None, str]:
        """Arch ``index`` and ``""``, or ``(None, "not an arch")`` when the draw of eq. (1) is
        no arch.

        Parameters
        ----------
        index : int
            Arch index, >= 0.

        Returns
        -------
        (BlockArch or None, str)
        """
        try:
            return self.arch(index), ""
        except ValueError:  # the nominal arch and epsilon are valid: the draw itself is not
            return None, "not an arch"

    def member(self, index: int, model: ModelSpec | str | None = None) -> SampledArch:
        """Arch ``index`` with its model, or the reason it is excluded (the rule of the module
        docstring).

        Parameters
        ----------
        index : int
            Arch index, >= 0.
        model : ModelSpec or str, optional
            The model and its settings (:func:`archquake.models.model_spec`; default the
            four-link model, restitution ``"computed"``); restitution ``"nominal"`` takes the
            nominal arch's coefficients (:func:`nominal_model`).

        Returns
        -------
        SampledArch

        Raises
        ------
        Exception
            Any error that is not one of :data:`EXCLUSIONS` (the caller names the arch,
            :func:`study_error`).
        """
        spec = model_spec(model)
        arch, why = self.draw(index)
        if arch is None:
            return SampledArch(int(index), None, None, why)
        nominal = nominal_model(self.nominal) if spec.needs_nominal else None
        built, why = analysable_model(arch, spec, nominal=nominal)
        return SampledArch(int(index), arch, built, why)

    def load_multipliers(self, indices, method: str) -> tuple[np.ndarray, np.ndarray]:
        r"""Limit analysis of arches of the sample: :math:`\tilde k_l, \tilde k_r` and why an
        arch is excluded.

        The values equal those of :func:`archquake.limit_analysis.limit_sample` with the same
        seed for the arches that stand; an arch that is not an arch or cannot stand (no thrust
        line: nan with the static method, a negative self-weight multiplier with the kinematic
        one) is excluded, with :math:`\tilde k` = nan; one that never collapses has inf.

        Parameters
        ----------
        indices : iterable of int
            Arch indices.
        method : {"static", "kinematic"}
            Limit-analysis method (:func:`archquake.limit_analysis.load_multipliers_of`).

        Returns
        -------
        k : ndarray, shape (n, 2)
            :math:`\tilde k_l, \tilde k_r` [-].
        excluded : ndarray of str, shape (n,)
            "" or a key of :data:`EXCLUSIONS`.
        """
        from ..limit_analysis import load_multipliers_of

        draws = [self.draw(i) for i in indices]
        arches = [arch for arch, _ in draws if arch is not None]
        k = np.full((len(draws), 2), np.nan)
        drawn = np.array([arch is not None for arch, _ in draws], dtype=bool)
        if arches:
            k[drawn] = load_multipliers_of(arches, method).reshape(-1, 2)
        why = np.array([why for _, why in draws], dtype="<U16")
        cannot_stand = drawn & np.any(np.isnan(k) | (k < 0.0), axis=1)
        why[cannot_stand] = "cannot stand"
        k[why != ""] = np.nan
        return k, why

    def label(self, index: int) -> str:
        """How a message names arch ``index``: its index and seed sequence.

        Parameters
        ----------
        index : int
            Arch index.

        Returns
        -------
        str
            ``"irregular arch i (SeedSequence(seed, spawn_key=(i,)))"``.
        """
        return f"irregular arch {index} (SeedSequence({self.seed}, spawn_key=({index},)))"


@dataclass(frozen=True, eq=False)
class BridgeSample:
    r"""Irregular bridges drawn around a bridge of several spans of one arch: member :math:`i`
    puts one irregular arch [paper, eq. (1)] on every span, drawn one after the other from
    ``SeedSequence(seed, spawn_key=(i,))``
    (:meth:`archquake.geometry.StructureSpec.member`), so that member :math:`i` of a study is
    member :math:`i` of ``archquake limit --spans N --epsilon E --seed S --samples n`` and of
    an assessment's irregular bridges. The same interface as :class:`ArchSample`, for the
    rigid-block model alone (a bridge has no four-link model).

    Parameters
    ----------
    description : StructureSpec
        The bridge, without ``epsilon`` and ``seed`` (the study's are used):
        :attr:`~archquake.geometry.StructureSpec.bridge_of_arches`.
    epsilon : float
        :math:`\varepsilon` of eq. (1) [-], in [0, 1).
    seed : int
        Root seed, >= 0.

    Raises
    ------
    ValueError
        For a description that is not a bridge of several spans of one arch, that draws its
        own irregular arch, or an epsilon or seed out of range.
    """

    description: Any
    epsilon: float
    seed: int

    def __post_init__(self) -> None:
        from ..geometry.spec import StructureSpec

        d = self.description
        if not isinstance(d, StructureSpec) or not d.bridge_of_arches:
            raise ValueError("description must be a StructureSpec of several spans of one arch "
                             f"(spans >= 2, no rings), got {d!r}")
        if d.epsilon is not None or d.seed is not None:
            raise ValueError("the description of a sampled bridge draws no irregular arch of "
                             "its own (epsilon and seed are the sample's)")
        object.__setattr__(self, "epsilon", check_epsilon(self.epsilon))
        object.__setattr__(self, "seed", check_integer("seed", self.seed, minimum=0))

    @property
    def nominal(self):
        """The bridge before the draw (:meth:`~archquake.geometry.StructureSpec.nominal`), built
        once per process and description: every chunk of a study reads its settings again."""
        return _bridge_nominal(json_dumps(self.description.to_dict(), sort_keys=True))

    @functools.cached_property
    def _drawing(self):
        from dataclasses import replace

        return replace(self.description, epsilon=self.epsilon, seed=self.seed)

    def arch(self, index: int):
        """Bridge ``index`` of the sample (a :class:`~archquake.geometry.BlockAssembly`).

        Raises
        ------
        ValueError
            If a span's draw is not an arch, or
            (:class:`~archquake.errors.UnseatedError`) the piers cannot seat the draws.
        """
        if self.epsilon == 0.0:
            return self.nominal
        return self._drawing.member(int(index))

    def draw(self, index: int):
        """Bridge ``index`` and ``""``, or ``(None, reason)``: ``"not an arch"`` when a span's
        draw is no arch, ``"not seated"`` when the piers cannot seat the draws."""
        from ..errors import UnseatedError

        try:
            return self.arch(index), ""
        except UnseatedError:
            return None, "not seated"
        except ValueError:
            return None, "not an arch"

    def member(self, index: int, model: ModelSpec | str | None = None) -> SampledArch:
        """Bridge ``index`` with its rigid-block model, or why it is excluded (as
        :meth:`ArchSample.member`; the standing check by the assembly's limit analysis)."""
        spec = model_spec(model)
        if spec.name != "rigid-blocks":
            raise ValueError(f"a bridge of several spans has no {spec.name} model: use the "
                             "rigid blocks")
        bridge, why = self.draw(index)
        if bridge is None:
            return SampledArch(int(index), None, None, why)
        model = spec.build(bridge)  # its multipliers, computed once, decide the standing
        k, why = _bridge_multipliers(lambda: model.load_multipliers)
        if why or all(math.isinf(x) for x in k):
            return SampledArch(int(index), bridge, None, why)
        return SampledArch(int(index), bridge, model, "")

    def load_multipliers(self, indices, method: str) -> tuple[np.ndarray, np.ndarray]:
        """``(k, excluded)`` of the bridges ``indices``, as :meth:`ArchSample.load_multipliers`:
        the assembly's limit analysis in both directions (``method`` is the study's, recorded;
        an assembly has the one static program)."""
        from ..limit_analysis import assembly_multipliers

        rows = []
        for i in indices:
            bridge, why = self.draw(i)
            k = (math.nan, math.nan)
            if bridge is not None:
                k, why = _bridge_multipliers(lambda b=bridge: assembly_multipliers(b))
            rows.append((k, why))
        k = np.array([r[0] for r in rows], dtype=float).reshape(-1, 2)
        return k, np.array([r[1] for r in rows], dtype="<U16")

    def label(self, index: int) -> str:
        """``"irregular bridge i (SeedSequence(seed, spawn_key=(i,)))"``."""
        return f"irregular bridge {index} (SeedSequence({self.seed}, spawn_key=({index},)))"


class StudySample:
    """What the settings of a study of irregular structures share to draw their sample: mixed
    into a frozen dataclass with the fields ``nominal`` (an arch), ``description`` (a bridge's
    :class:`~archquake.geometry.StructureSpec`, or None), ``epsilon``, ``seed`` and ``model``
    (:class:`~archquake.studies.fragility.FragilitySettings`,
    :class:`~archquake.studies.record_fragility.RecordFragilitySettings`)."""

    def _take_description(self) -> None:
        """With a bridge's description: check it and the model (the rigid blocks alone), and
        make its bridge the nominal structure."""
        if self.description is None:
            return
        bridges = BridgeSample(self.description, self.epsilon, self.seed)
        if model_spec(self.model).name != "rigid-blocks":
            raise ValueError("a bridge of several spans has no four-link model: a study of one "
                             "takes the rigid blocks (model 'rigid-blocks')")
        object.__setattr__(self, "nominal", bridges.nominal)

    @property
    def sample(self) -> ArchSample | BridgeSample:
        """The irregular structures of the study: :class:`ArchSample` ``(nominal, epsilon,
        seed)``, or for a bridge :class:`BridgeSample` ``(description, epsilon, seed)``; member
        ``i`` drawn from ``SeedSequence(seed, spawn_key=(i,))``."""
        if self.description is not None:
            return BridgeSample(self.description, self.epsilon, self.seed)
        return ArchSample(self.nominal, self.epsilon, self.seed)

    def engines(self) -> list[tuple[str, Any]]:
        """The compiled engines the study runs (:mod:`archquake.compiled`): its model's, and
        its screen's (the settings' ``screening``, None without one)."""
        screening = self.screening
        return self.model.engines() + ([] if screening is None else screening.engines())

    @property
    def member_nouns(self) -> tuple[str, str]:
        """How the outputs name one member of the sample and several: ``("arch", "arches")``,
        or ``("bridge", "bridges")``."""
        return ("bridge", "bridges") if self.description is not None else ("arch", "arches")

    @property
    def nominal_structure(self) -> BlockArch | BridgeSample:
        """What identifies the nominal structure to :func:`nominal_model`: the nominal arch, or
        a bridge's sample (its description)."""
        return self.nominal if self.description is None else self.sample

    def structure_dict(self) -> dict:
        """``{"nominal": arch dict}``, or for a bridge ``{"description": its fields}`` (which
        builds the nominal bridge), as the settings store them."""
        if self.description is not None:
            return {"description": self.description.to_dict()}
        return {"nominal": self.nominal.to_dict()}

    @staticmethod
    def structure_of(data: dict) -> dict:
        """Inverse of :meth:`structure_dict`: the fields ``nominal`` and ``description``."""
        from ..geometry.spec import StructureSpec
        from ..reference_arches import oppenheim

        if data.get("description") is not None:  # a bridge: its nominal is the description's
            return {"nominal": oppenheim(),
                    "description": StructureSpec.from_dict(data["description"])}
        return {"nominal": arch_from_dict(data["nominal"]), "description": None}


def sample_of(data: dict, seed: int) -> ArchSample | BridgeSample:
    """The sample a study's settings draw (``nominal`` or a bridge's ``description``, and
    ``epsilon``), with the root seed ``seed``.

    Parameters
    ----------
    data : dict
        ``{"nominal": arch dict, "epsilon": e}`` or ``{"description": StructureSpec dict,
        "epsilon": e}`` (:meth:`archquake.studies.fragility.FragilitySettings.to_sample_dict`).
    seed : int
        Root seed, >= 0.

    Returns
    -------
    ArchSample or BridgeSample
    """
    structure = StudySample.structure_of(data)
    if structure["description"] is not None:
        return BridgeSample(structure["description"], data["epsilon"], seed)
    return ArchSample(structure["nominal"], data["epsilon"], seed)


@functools.lru_cache(maxsize=8)
def _bridge_nominal(description: str):
    from ..geometry.spec import StructureSpec

    return StructureSpec.from_dict(json.loads(description)).nominal()


def _bridge_multipliers(multipliers) -> tuple[tuple[float, float], str]:
    """``((k_l, k_r), "")`` of a bridge from ``multipliers()``, its limit analysis
    (:func:`archquake.limit_analysis.assembly_multipliers`, what its rigid-block model states,
    :attr:`archquake.rigid_blocks.RigidBlockModel.load_multipliers`), or ``((nan, nan),
    "cannot stand")``."""
    from ..errors import CannotStandError

    try:
        k = multipliers()
    except CannotStandError:
        return (math.nan, math.nan), "cannot stand"
    if any(math.isnan(x) or x < 0.0 for x in k):
        return (math.nan, math.nan), "cannot stand"
    return k, ""


def analysable_model(arch: BlockArch, model: ModelSpec | str | None = None, *,
                     nominal=None) -> tuple[Any, str]:
    """The model of an arch, or why the arch cannot be analysed (:data:`EXCLUSIONS`).

    The rule is the same for both models where it can be: an arch that cannot stand (no line
    of thrust under its own weight, by the limit analysis) is excluded, and one with no
    collapse mechanism in either direction is analysed as at rest. "not analysable" (a collapse
    mechanism that is no four-link mechanism) is the four-link model's alone: the rigid blocks
    take any mechanism.

    Parameters
    ----------
    arch : BlockArch
        The arch.
    model : ModelSpec or str, optional
        The model and its settings (:func:`archquake.models.model_spec`).
    nominal : BlockArch or FourLinkModel, optional
        The nominal arch, for ``restitution="nominal"``.

    Returns
    -------
    (StructuralModel or None, str)
        ``(model, "")``; ``(None, "")`` for an arch that never collapses in either direction
        (analysed: it stays at rest); ``(None, reason)`` for an excluded one.

    Raises
    ------
    Exception
        Any error of building the model other than those of :data:`EXCLUSIONS`.
    """
    from ..errors import CannotStandError, NeverCollapsesError
    from ..limit_analysis import load_multipliers

    spec = model_spec(model)
    try:
        if spec.checks_standing:
            k = np.asarray(load_multipliers(arch), dtype=float)  # the same verdict on standing
            if np.any(np.isnan(k) | (k < 0.0)):
                raise CannotStandError("the arch cannot stand under its own weight")
            if np.all(np.isinf(k)):
                raise NeverCollapsesError("no collapse mechanism in either direction")
        return spec.build(arch, nominal), ""
    except CannotStandError:
        return None, "cannot stand"
    except NeverCollapsesError:
        if np.all(np.isinf(load_multipliers(arch))):
            return None, ""
        return None, "not analysable"
    except ValueError:
        return None, "not analysable"


def nominal_json(nominal: BlockArch | BridgeSample) -> str:
    """The nominal arch as canonical JSON text (sorted keys): what identifies it in a study.

    Parameters
    ----------
    nominal : BlockArch or BridgeSample
        The arch, or the sample of a bridge (identified by its description).

    Returns
    -------
    str
        ``json.dumps(nominal.to_dict(), sort_keys=True)``.
    """
    if isinstance(nominal, BridgeSample):  # a bridge's nominal structure: its description's
        return json_dumps({"description": nominal.description.to_dict()}, sort_keys=True)
    return json_dumps(nominal.to_dict(), sort_keys=True)


@functools.lru_cache(maxsize=8)
def _model_of(nominal: str, model: ModelSpec):
    data = json.loads(nominal)
    if "description" in data:  # a bridge: the one its sample built (_bridge_nominal)
        return model.build(_bridge_nominal(json_dumps(data["description"], sort_keys=True)))
    return model.build(arch_from_dict(data))


def nominal_model(nominal: BlockArch | BridgeSample, model: ModelSpec | str | None = None):
    """The model of the nominal arch, built once per process and (arch, model spec).

    Every chunk of a study needs it (its mechanisms for ``restitution="nominal"``, the record
    study's nominal arch); building it (limit analyses, linkage, tables) in every chunk cost
    about a tenth of a chunk. Models are frozen values, so sharing one changes no result.

    Parameters
    ----------
    nominal : BlockArch or BridgeSample
        The nominal arch (identified by :func:`nominal_json`), or the sample of a bridge (its
        nominal bridge).
    model : ModelSpec or str, optional
        The model and its settings (:func:`archquake.models.model_spec`; default the four-link
        model, restitution ``"computed"``).

    Returns
    -------
    StructuralModel

    Raises
    ------
    ValueError
        If the arch cannot be analysed (:func:`check_nominal` says so in a study's words).
    """
    return _model_of(nominal_json(nominal), model_spec(model))


def check_nominal(nominal: BlockArch | BridgeSample, model: ModelSpec | str | None = None):
    """Refuse, before any study, a nominal arch that cannot be analysed (e.g. it cannot stand
    under its own weight): every result of a study is compared with it.

    Parameters
    ----------
    nominal : BlockArch or BridgeSample
        The nominal arch, or the sample of a bridge.
    model : ModelSpec or str, optional
        The model and its settings (:func:`archquake.models.model_spec`).

    Returns
    -------
    StructuralModel
        :func:`nominal_model`.

    Raises
    ------
    ValueError
        ``"the nominal arch cannot be analysed: ..."``.
    """
    try:
        return nominal_model(nominal, model)
    except ValueError as exc:
        raise ValueError(f"the nominal arch cannot be analysed: {exc}") from exc


def study_error(label: str, exc: BaseException):
    """The error that stops a study when an arch fails for a reason other than
    :data:`EXCLUSIONS`, naming the arch.

    Parameters
    ----------
    label : str
        The arch (:meth:`ArchSample.label`, or ``"the nominal arch"``).
    exc : BaseException
        What it raised.

    Returns
    -------
    archquake.errors.StudyError or KeyboardInterrupt
        ``"<label> stopped the study: <type>: <message>"`` (raise it ``from exc``); the
        interrupt itself when ``exc`` is Ctrl-C surfacing from compiled code as a
        ``SystemError`` (:func:`archquake.errors.interrupt_in`): the study is interrupted,
        not stopped by the arch.
    """
    from ..errors import StudyError, interrupt_in

    interrupt = interrupt_in(exc)
    if interrupt is not None:
        return interrupt
    return StudyError(f"{label} stopped the study: {type(exc).__name__}: {exc}")


def excluded_arches(table) -> dict[int, str]:
    """The excluded arches of a study table (column ``excluded``, :data:`EXCLUSIONS`).

    Parameters
    ----------
    table : pandas.DataFrame
        A study table with the columns ``arch`` and ``excluded``.

    Returns
    -------
    dict of int to str
        ``{arch: reason}``; empty for a table without the column ``excluded`` (a study written
        before the column existed excluded nothing).
    """
    if "excluded" not in table.columns:
        return {}
    why = table["excluded"].fillna("").astype(str)  # "" reads back from CSV as missing
    rows = table.loc[why != "", ["arch"]].assign(why=why[why != ""]).drop_duplicates("arch")
    return {int(i): str(w) for i, w in zip(rows["arch"], rows["why"], strict=True)}


def exclusion_summary(drawn: int, excluded: dict[int, str]) -> dict:
    """How many arches a study drew and analysed, and the excluded ones by reason.

    Parameters
    ----------
    drawn : int
        Number of arches drawn (the settings' sample size).
    excluded : dict of int to str
        ``{arch: reason}`` (:func:`excluded_arches`).

    Returns
    -------
    dict
        ``{"drawn": n, "analysed": n - len(excluded), "excluded": {reason: [arches]}}``, the
        reasons in the order of :data:`EXCLUSIONS`.
    """
    reasons = sorted(set(excluded.values()), key=list(EXCLUSIONS).index)
    return {"drawn": int(drawn), "analysed": int(drawn) - len(excluded),
            "excluded": {why: sorted(i for i, w in excluded.items() if w == why)
                         for why in reasons}}


def check_analysed(drawn: int, excluded: dict[int, str], epsilon: float) -> None:
    """Refuse a study whose every arch was excluded: it has no probability to estimate.

    Parameters
    ----------
    drawn : int
        Number of arches drawn.
    excluded : dict of int to str
        ``{arch: reason}``.
    epsilon : float
        The sample's epsilon [-] (for the message).

    Raises
    ------
    ValueError
        ``"every one of the <drawn> irregular arches was excluded (...)"``, with the counts by
        reason and what to change.
    """
    if len(excluded) < drawn:
        return
    counts = ", ".join(f"{why}: {len(items)}" for why, items in
                       exclusion_summary(drawn, excluded)["excluded"].items())
    piers = (" (or wider piers, for the draws they cannot seat)"
             if "not seated" in excluded.values() else "")
    raise ValueError(f"every one of the {drawn} irregular arches was excluded ({counts}): no "
                     f"probability of failure can be estimated; use a smaller epsilon (epsilon "
                     f"= {epsilon:g}) or a thicker nominal arch{piers}")


__all__ = [
    "EXCLUSIONS", "NEVER_COLLAPSES", "STATUS_EXCLUDED", "ArchSample", "BridgeSample",
    "SampledArch", "StudySample",
    "analysable_model", "check_analysed", "check_nominal", "exclusion_summary",
    "excluded_arches", "nominal_json", "nominal_model", "sample_of", "study_error",
]
