"""What a campaign run needs on a cluster worker: the case text and the files it names.

A Dask worker may run in another folder, on another machine, with nothing of the client's
disk. The client therefore resolves a campaign's cases into one :class:`RunBundle`: the
case file's path as given (kept as the runs' ``case_file``, so messages and run files read
as a local run's), its text, and every file any run of the campaign reads, keyed by the
SHA-256 of its bytes:

* ``case/NAME``: a file the case names relative to its folder (a motion table, a body-motion
  table, a hull mesh; :func:`floatmoor.case.files.resolve_case_file`), under the name the case
  writes (after the run's overrides), so the case text finds it unchanged;
* ``hydrodb/NAME.nc``: the hydrodynamic database of a floater case
  (:func:`floatmoor.hydro.database.database_path` on the client).

The worker writes each distinct content once into a private folder
(:func:`materialise`: ``blobs/SHA256``, checked against its hash, linked into the bundle's own
folder ``bundles/BUNDLE_HASH``) and loads the run's case from there
(:func:`load_bundled_case`); the bytes themselves travel separately (scattered once per worker
by :mod:`floatmoor.campaign.cluster`).
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any, Mapping, Sequence

from floatmoor.case.limits import parse_toml
from floatmoor.case.load import parse_case
from floatmoor.case.overrides import apply_overrides
from floatmoor.case.schema import BodyTableMotion, Case, MeshGeometry, TableMotion
from floatmoor.errors import FloatmoorError
from floatmoor.io.output_files import atomic_target

__all__ = ["RunBundle", "BundleError", "make_bundle", "materialise", "load_bundled_case",
           "CASE_FOLDER", "DATABASE_FOLDER"]

#: The bundle folder holding the files named relative to the case file's folder.
CASE_FOLDER = "case"
#: The bundle folder holding the hydrodynamic databases (``hydrodb/NAME.nc``).
DATABASE_FOLDER = "hydrodb"


class BundleError(FloatmoorError):
    """A bundle's file is missing, does not match its hash, or would leave its folder."""


@dataclass(frozen=True)
class RunBundle:
    """A campaign's case as a worker rebuilds it.

    Attributes
    ----------
    case_source
        The case file's path as the client was given it (the runs' ``case.source``).
    case_text
        The case file's text.
    files
        Bundle-relative POSIX path -> SHA-256 (hex) of the bytes to put there.
    """

    case_source: str
    case_text: str
    files: dict[str, str] = field(default_factory=dict)

    @property
    def key(self) -> str:
        """SHA-256 of the bundle's contents: the name of its folder on a worker."""
        text = json.dumps([self.case_source, self.case_text, sorted(self.files.items())])
        return hashlib.sha256(text.encode()).hexdigest()


def _written_name(case: Case, keys: Sequence[str]) -> str:
    """The value at ``keys`` of the case table after the run's overrides (a file name as the
    case writes it, which a loaded case keeps only resolved)."""
    raw = parse_toml(case.text, case.source)
    apply_overrides(raw, case.overrides, case.source)
    value: Any = raw
    for key in keys:
        value = value[key]
    return str(value)


def _case_files(case: Case) -> dict[str, Path]:
    """Bundle-relative path -> the client's file, of every file ``case`` reads."""
    from floatmoor.hydro.database import database_file_name, database_path

    named: list[tuple[str, str]] = []  # (name as written, resolved path)
    if isinstance(case.motion, (TableMotion, BodyTableMotion)):
        named.append((_written_name(case, ("motion", "file")), case.motion.file))
    if case.floater is not None and isinstance(case.floater.geometry, MeshGeometry):
        geometry = case.floater.geometry
        assert geometry.path is not None  # read from the case file, so resolved
        named.append((geometry.file, geometry.path))
    files = {_inside(CASE_FOLDER, name): Path(path) for name, path in named}
    if case.floater is not None and case.hydro is not None:
        files[_inside(DATABASE_FOLDER, database_file_name(case.hydro))] = database_path(case)
    return files


def _inside(folder: str, name: str) -> str:
    """``folder/name`` normalised; refused when ``name`` leads out of ``folder``."""
    path = PurePosixPath(os.path.normpath(PurePosixPath(folder, name)))
    if path.is_absolute() or path.parts[:1] != (folder,) or len(path.parts) < 2:
        raise BundleError(f"the file name '{name}' leads out of the bundle's {folder}/ folder")
    return str(path)


def make_bundle(cases: Sequence[Case]) -> tuple[RunBundle, dict[str, bytes]]:
    """The bundle of a campaign whose runs load as ``cases`` (all from one case file), and
    the bytes of its files by SHA-256.

    Raises
    ------
    BundleError
        When two runs put different files at one bundle path (not possible for the cases
        of one case file, whose names are confined to its folder), or a file cannot be read.
    """
    first = cases[0]
    paths: dict[str, Path] = {}
    for case in cases:
        for name, path in _case_files(case).items():
            if paths.setdefault(name, path) != path:
                raise BundleError(f"{name}: two runs read different files there "
                                  f"({paths[name]} and {path})")
    files: dict[str, str] = {}
    blobs: dict[str, bytes] = {}
    for name, path in sorted(paths.items()):
        try:
            data = path.read_bytes()
        except OSError as err:
            raise BundleError(f"{path}: cannot be read to send to the workers "
                              f"({err.strerror})") from None
        digest = hashlib.sha256(data).hexdigest()
        files[name] = digest
        blobs[digest] = data
    return RunBundle(first.source, first.text, files), blobs


def materialise(bundle: RunBundle, blobs: Mapping[str, bytes], root: Path) -> Path:
    """The bundle's folder under ``root``, with every file in place; returns it.

    Each distinct content is written once (``root/blobs/SHA256``, after checking the bytes
    against their hash) and hard-linked (copied where links fail) into
    ``root/bundles/KEY``; files already there are reused, so runs of one campaign on one
    worker write nothing after the first. Safe for concurrent tasks: every file appears
    whole (written beside and renamed).

    Raises
    ------
    BundleError
        When bytes are missing or do not have their recorded SHA-256, or a path would
        leave the bundle's folder.
    """
    store = root / "blobs"
    folder = root / "bundles" / bundle.key
    store.mkdir(parents=True, exist_ok=True)
    for name, digest in bundle.files.items():
        top, _, rest = name.partition("/")
        if top not in (CASE_FOLDER, DATABASE_FOLDER) or _inside(top, rest) != name:
            raise BundleError(f"{name}: not a path inside the bundle's {CASE_FOLDER}/ or "
                              f"{DATABASE_FOLDER}/ folder")
        target = folder / name
        if target.is_file():
            continue
        blob = store / digest
        if not blob.is_file():
            data = blobs.get(digest)
            if data is None or hashlib.sha256(data).hexdigest() != digest:
                raise BundleError(f"{name}: the bytes received do not have the SHA-256 "
                                  f"{digest} the client sent")
            with atomic_target(blob) as tmp:
                tmp.write_bytes(data)
        target.parent.mkdir(parents=True, exist_ok=True)
        with atomic_target(target) as tmp:
            tmp.unlink()
            try:
                os.link(blob, tmp)
            except OSError:
                tmp.write_bytes(blob.read_bytes())
    (folder / CASE_FOLDER).mkdir(parents=True, exist_ok=True)
    return folder


def load_bundled_case(bundle: RunBundle, folder: Path, overrides: Sequence[str]
                      ) -> tuple[Case, Path | None]:
    """The run's case, loaded from the bundle's text with its files found in ``folder``
    (:func:`materialise`), and the path of its hydrodynamic database there (None without a
    floater).

    The case keeps the client's ``source``, so it reads (in messages and run files) as the
    case loaded on the client.

    Raises
    ------
    CaseError
        As :func:`floatmoor.case.load.load_case`.
    """
    raw = parse_toml(bundle.case_text, bundle.case_source)
    case = parse_case(raw, source=bundle.case_source, text=bundle.case_text,
                      overrides=tuple(overrides), base_dir=folder / CASE_FOLDER)
    database = None
    if case.floater is not None and case.hydro is not None:
        from floatmoor.hydro.database import database_file_name

        database = folder / _inside(DATABASE_FOLDER, database_file_name(case.hydro))
    return case, database
