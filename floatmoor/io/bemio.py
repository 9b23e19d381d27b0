"""WEC-Sim BEMIO HDF5 files (``.h5``) -> :class:`ImportedBem`.

A small strict reader of the file WEC-Sim's BEMIO writes (``writeBEMIOH5.m``) and WEC-Sim
reads (``readBEMIOH5.m``), one rigid body of six DOFs. The layout, the dimension order and
the normalisation below were taken from WEC-Sim's own source (repository WEC-Sim/WEC-Sim,
``source/functions/BEMIO/``: ``writeBEMIOH5.m``, ``readBEMIOH5.m``, ``readH5ToStruct.m``,
``reverseDimensionOrder.m``, ``normalizeBEM.m``, ``radiationIRF.m``, ``readWAMIT.m``,
``readCAPYTAINE.m``) and its BEMIO documentation (``docs/_include/bemio.rst``, the *hydro*
structure).

Layout (``N`` the body number, ``Nf`` frequencies, ``Nh`` wave directions, ``n`` = 6 x the
number of bodies; shapes as h5py reads them)::

    /simulation_parameters/w, T        (Nf, 1)   [rad/s], [s]
    /simulation_parameters/wave_dir    (Nh, 1)   [deg] (the dataset's ``units``)
    /simulation_parameters/rho, g      (1, 1)
    /simulation_parameters/water_depth (1, 1) [m], or the string "infinite"
    /simulation_parameters/scaled      (1, 1)    0: normalised values (BEMIO writes 0)
    /bem_data/code                     string    the BEM program (optional here)
    /bodyN/properties/name, body_number, cg (3, 1), cb (3, 1), disp_vol (1, 1)
    /bodyN/properties/dof, dof_start, dof_end   (optional; 6, 6 N - 5, 6 N)
    /bodyN/hydro_coeffs/linear_restoring_stiffness          (6, 6)       C / (rho g)
    /bodyN/hydro_coeffs/added_mass/all                      (6, n, Nf)   A / rho
    /bodyN/hydro_coeffs/added_mass/inf_freq                 (6, n)       A_inf / rho
    /bodyN/hydro_coeffs/radiation_damping/all               (6, n, Nf)   B / (rho omega)
    /bodyN/hydro_coeffs/excitation/re, im                   (6, Nh, Nf)  X / (rho g)
    /bodyN/hydro_coeffs/excitation/froude-krylov/re, im     (optional, as excitation)
    /bodyN/hydro_coeffs/excitation/scattering/re, im        (optional, as excitation)

MATLAB writes column-major: BEMIO permutes its ``hydro.A(i, j, f)`` to ``(f, j, i)`` before
writing, so h5py (row-major) sees ``(i, j, f)`` again; a 1 x Nf MATLAB row reads as (Nf, 1).
BEMIO's ``A(i, j)`` is WAMIT's: the force in DOF i due to the motion of DOF j (its
``readCAPYTAINE`` permutes capytaine's arrays to (influenced, radiating)), so ``all[i, j, f]``
goes to floatmoor's ``added_mass[f, j, i]``; ``linear_restoring_stiffness[i, j]`` is
``C(i, j)`` as floatmoor's. BEMIO's complex amplitudes follow WAMIT's e^{+i omega t}
(``readCAPYTAINE`` negates capytaine's imaginary parts): floatmoor stores the conjugate.
Wave directions are propagation directions, as floatmoor's.

Multi-body files: ``body`` selects one; its coupling blocks with the other bodies (the
columns of their DOFs) are dropped, with a note. Anything missing, of the wrong shape, NaN,
or inconsistent (frequencies not positive or repeated, T not 2 pi / omega) raises
:class:`BemFileError` naming the file and the HDF5 path.

A BEMIO file is data from elsewhere (docs/guide/safeguards.md#files-from-elsewhere): the file
must be a regular file of at most :data:`MAX_FILE_BYTES`; only datasets stored in the file
itself are read (soft and external links, virtual datasets and external raw storage are
refused), of a floating-point type (strings where a string is expected), their shape checked
against the expected one before their data are read, and at most :data:`MAX_READ_BYTES` of data
in all. Text from the file (names, entries) is quoted with
:func:`floatmoor.terminal_text.shown`. Mean drift datasets, when present, are read by
:mod:`floatmoor.io.bemio_second_order`.

Size: one strict reader of one file layout: the dataset access, the checks and the assembly of
one body share the open file and its notes; split, each part would need the others.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.io.bem_data import BemFileError, ImportedBem
from floatmoor.io.bemio_second_order import read_bemio_mean_drift
from floatmoor.input_files import InputFileError, open_regular
from floatmoor.terminal_text import shown

__all__ = ["read_bemio", "MAX_FILE_BYTES", "MAX_READ_BYTES", "MAX_TEXT_BYTES", "MAX_BODIES"]

_N_DOF = 6

#: Agreement required between ``T`` and ``2 pi / w``, relative: BEMIO derives one from the
#: other in double precision (readCAPYTAINE, readNEMOH) or from WAMIT's printed periods
#: (readWAMIT, ~5e-7); 1e-5 passes both and catches a T belonging to another frequency set.
PERIOD_RTOL = 1e-5

#: Agreement required between the excitation and the sum of its Froude-Krylov and scattering
#: parts, relative to the DOF's largest excitation over the file: BEMIO forms the total as
#: the sum (readCAPYTAINE) or reads both from one WAMIT run; 1e-3 catches parts from another
#: run.
PARTS_SUM_RTOL = 1e-3

#: Largest BEMIO file opened [bytes]: a real file of hundreds of frequencies and wave directions
#: and a few bodies holds a few MB to tens of MB (6 x 60 x 1000 x 8 bytes = 2.9 MB for the
#: added mass of ten bodies at 1000 frequencies); the bytes of a variable-length string lie
#: uncompressed in the file, so this also bounds the longest string HDF5 can hand back.
MAX_FILE_BYTES = 256 * 2**20
#: Most data read from one file [bytes, as float64], summed over the datasets read and checked
#: before each is read: a compressed dataset can declare far more data than its file holds (a
#: few kB declaring (6, 6, 2e9) values), and this bounds the memory an import takes whatever a
#: file declares (the same figure as :data:`MAX_FILE_BYTES`).
MAX_READ_BYTES = 256 * 2**20
#: Longest string read (body name, BEM code, water depth "infinite", units) [bytes]: such names
#: are tens of characters.
MAX_TEXT_BYTES = 4096
#: Most bodies a file may number (body1 .. bodyN): BEMIO files of wave farms hold tens.
MAX_BODIES = 10_000

_BODY_GROUP = re.compile(r"body([1-9][0-9]{0,5})$")


class _File:
    """An open BEMIO file with strict dataset access (every error names the HDF5 path).

    Only what the file itself stores is read (:func:`_entry`): an entry reached through a soft
    or external link, a virtual dataset or one with external raw storage (bytes kept in another
    file, e.g. ``/etc/passwd``) is refused before any data are read; so is a dataset of another
    type or shape than expected, or one that would take the read past :data:`MAX_READ_BYTES`.
    """

    def __init__(self, handle: Any, name: str) -> None:
        self.h5 = handle
        self.name = name
        self.read_bytes = 0

    def error(self, where: str, expected: str, found: str) -> BemFileError:
        return BemFileError(self.name, where, expected, found)

    def _entry(self, where: str, what: str) -> Any:
        """The object at ``where`` reached through hard links only (None when absent)."""
        import h5py

        node = self.h5
        walked = ""
        for part in [p for p in where.split("/") if p]:
            walked += "/" + part
            if not isinstance(node, h5py.Group):
                return None
            link = node.get(part, getlink=True)
            if link is None:
                return None
            if not isinstance(link, h5py.HardLink):
                kind = ("an external link to another file" if isinstance(link, h5py.ExternalLink)
                        else "a soft link" if isinstance(link, h5py.SoftLink) else "a link")
                raise self.error(walked, f"{what} stored in the file itself", kind)
            node = node[part]
        return node

    def has(self, where: str) -> bool:
        import h5py

        return isinstance(self._entry(where, "an entry"), h5py.Dataset)

    def has_group(self, where: str) -> bool:
        import h5py

        return isinstance(self._entry(where, "an entry"), h5py.Group)

    def raw(self, where: str, what: str) -> Any:
        """The dataset at ``where``, stored in the file itself (no data read yet)."""
        import h5py

        obj = self._entry(where, f"a dataset ({what})")
        if obj is None:
            raise self.error(where, f"a dataset ({what})", "none")
        if not isinstance(obj, h5py.Dataset):
            raise self.error(where, f"a dataset ({what})", "a group")
        if obj.shape is None:
            raise self.error(where, f"a dataset ({what})", "an empty (null) dataset")
        if obj.is_virtual:
            raise self.error(where, f"a dataset ({what}) stored in the file itself",
                             "a virtual dataset (data mapped from other datasets or files)")
        if obj.id.get_create_plist().get_external_count():
            raise self.error(where, f"a dataset ({what}) stored in the file itself",
                             "a dataset with external raw storage (its bytes in another file)")
        return obj

    def _budget(self, where: str, what: str, count: int, item: int = 8) -> None:
        """Account for ``count`` values of ``item`` bytes, refusing what passes the budget."""
        size = count * item
        if self.read_bytes + size > MAX_READ_BYTES:
            raise self.error(where, f"at most {MAX_READ_BYTES} bytes of data in the file "
                             f"({what})", f"{count} values ({size} bytes) after "
                             f"{self.read_bytes} bytes read")
        self.read_bytes += size

    def _values(self, data: Any, where: str) -> NDArray[np.float64]:
        try:
            return np.asarray(data[()], dtype=float)
        except (OSError, RuntimeError, ValueError, TypeError) as err:
            raise self.error(where, "data HDF5 can read", shown(err)) from None

    def _numbers(self, where: str, what: str) -> Any:
        data = self.raw(where, what)
        if _type_class(data.id.get_type()) != "floating-point numbers":
            raise self.error(where, f"floating-point numbers ({what})",
                             _type_text(data.id.get_type()))
        return data

    def array(self, where: str, what: str, shape: tuple[int, ...]) -> NDArray[np.float64]:
        """A floating-point dataset of exactly ``shape``, finite."""
        values = self.float_array(where, what, shape)
        self.finite(where, values)
        return values

    def float_array(self, where: str, what: str, shape: tuple[int, ...]
                    ) -> NDArray[np.float64]:
        """A floating-point dataset of exactly ``shape`` (checked before it is read)."""
        data = self._numbers(where, what)
        if tuple(data.shape) != shape:
            raise self.error(where, f"shape {shape} ({what})", f"shape {tuple(data.shape)}")
        self._budget(where, what, math.prod(shape))
        return self._values(data, where)

    def finite(self, where: str, values: NDArray[np.float64]) -> None:
        bad = np.argwhere(~np.isfinite(values))
        if bad.size:
            index = tuple(int(k) for k in bad[0])
            raise self.error(where, "finite numbers",
                             f"{values[index]} at index {list(index)} "
                             f"({len(bad)} such value{'s' if len(bad) > 1 else ''})")

    def vector(self, where: str, what: str, size: int | None = None) -> NDArray[np.float64]:
        """A floating-point dataset with one non-singleton dimension (MATLAB rows and
        columns)."""
        data = self._numbers(where, what)
        shape = tuple(data.shape)
        if sum(n > 1 for n in shape) > 1:
            raise self.error(where, f"a vector ({what})", f"shape {shape}")
        count = math.prod(shape)
        if size is not None and count != size:
            raise self.error(where, f"{size} value{'s' if size > 1 else ''} ({what})",
                             f"{count} (shape {shape})")
        self._budget(where, what, count)
        flat = self._values(data, where).reshape(-1)
        self.finite(where, flat)
        return flat

    def scalar(self, where: str, what: str) -> float:
        return float(self.vector(where, what, 1)[0])

    def text(self, where: str, what: str) -> str:
        """A string dataset of one element (fixed length at most :data:`MAX_TEXT_BYTES`)."""
        data = self.raw(where, what)
        self._string_type(data.id.get_type(), data.shape, where, what)
        try:
            value = data[()]
        except (OSError, RuntimeError, ValueError, TypeError) as err:
            raise self.error(where, "data HDF5 can read", shown(err)) from None
        if isinstance(value, np.ndarray):
            value = value.reshape(-1)[0]
        if isinstance(value, (bytes, np.bytes_)):
            value = bytes(value).decode("utf-8", errors="replace").rstrip("\x00")
        if not isinstance(value, str):
            raise self.error(where, f"a string ({what})", f"data of type {type(value).__name__}")
        if len(value) > MAX_TEXT_BYTES:
            raise self.error(where, f"a string of at most {MAX_TEXT_BYTES} characters "
                             f"({what})", f"{len(value)} characters")
        return value.strip()

    def _string_type(self, tid: Any, shape: tuple[int, ...], where: str, what: str) -> None:
        """Refuse all but one string of fixed length <= MAX_TEXT_BYTES, before reading."""
        if _type_class(tid) != "a string" or math.prod(shape) != 1:
            raise self.error(where, f"a string ({what})",
                             f"{_type_text(tid)}, shape {tuple(shape)}")
        if not tid.is_variable_str() and tid.get_size() > MAX_TEXT_BYTES:
            raise self.error(where, f"a string of at most {MAX_TEXT_BYTES} bytes ({what})",
                             f"a string type of {tid.get_size()} bytes")

    def attribute_text(self, data: Any, where: str, name: str, default: str) -> str:
        """String attribute ``name`` of ``data`` (or ``default``), checked before reading."""
        if name not in data.attrs:
            return default
        attr = data.attrs.get_id(name)
        at = f"{where} (attribute '{name}')"
        self._string_type(attr.get_type(), attr.shape or (), at, name)
        value = data.attrs[name]
        if isinstance(value, np.ndarray):
            value = value.reshape(-1)[0]
        value = value.decode("utf-8", errors="replace") if isinstance(value, bytes) \
            else str(value)
        if len(value) > MAX_TEXT_BYTES:
            raise self.error(at, f"a string of at most {MAX_TEXT_BYTES} characters",
                             f"{len(value)} characters")
        return value


def _type_class(tid: Any) -> str:
    """What an HDF5 type holds, read from the type itself (numpy cannot represent every
    HDF5 type: a 3e9-byte string type makes ``Dataset.dtype`` raise)."""
    from h5py import h5t

    return {h5t.FLOAT: "floating-point numbers", h5t.INTEGER: "integers",
            h5t.STRING: "a string"}.get(tid.get_class(), "another type")


def _type_text(tid: Any) -> str:
    return f"data of type {_type_class(tid)} ({tid.get_size()} bytes per value)"


def _bodies(file: _File) -> list[int]:
    keys = list(file.h5.keys())
    numbers = sorted(int(m.group(1)) for key in keys if (m := _BODY_GROUP.match(key)))
    if not numbers:
        raise file.error("/", "groups body1, body2, ... (a WEC-Sim BEMIO file)",
                         "none; top-level entries: " + shown(", ".join(sorted(keys))))
    if numbers != list(range(1, len(numbers) + 1)):
        raise file.error("/", f"body groups numbered 1..{len(numbers)}",
                         shown(", ".join(f"body{n}" for n in numbers)))
    if len(numbers) > MAX_BODIES:
        raise file.error("/", f"at most {MAX_BODIES} body groups", f"{len(numbers)}")
    return numbers


def _count(file: _File, where: str, what: str) -> int:
    """A whole number 0..6 x :data:`MAX_BODIES` (a DOF count or index)."""
    value = file.scalar(where, what)
    if value != round(value) or not 0 <= value <= _N_DOF * MAX_BODIES:
        raise file.error(where, f"a whole number from 0 to {_N_DOF * MAX_BODIES} ({what})",
                         f"{value:g}")
    return int(value)


def _dof_range(file: _File, number: int) -> tuple[int, int, int]:
    """(dof, first column, end column) of body ``number`` in the coupled matrices."""
    base = f"/body{number}/properties/"
    dof = _count(file, base + "dof", "DOFs") if file.has(base + "dof") else _N_DOF
    start = (_count(file, base + "dof_start", "first DOF") if file.has(base + "dof_start")
             else (number - 1) * _N_DOF + 1)
    end = (_count(file, base + "dof_end", "last DOF") if file.has(base + "dof_end")
           else start + dof - 1)
    if end - start + 1 != dof or start < 1:
        raise file.error(base + "dof_end", f"dof_start + dof - 1 = {start + dof - 1}",
                         f"{end} (dof_start = {start}, dof = {dof})")
    return dof, start - 1, end


def _water_depth(file: _File) -> float:
    where = "/simulation_parameters/water_depth"
    data = file.raw(where, "water depth [m] or 'infinite'")
    if _type_class(data.id.get_type()) == "a string":
        text = file.text(where, "water depth")
        if text.lower() in ("infinite", "inf"):
            return math.inf
        raise file.error(where, "a depth [m] or the string 'infinite'", f"'{shown(text)}'")
    depth = file.scalar(where, "water depth [m]")
    if depth <= 0.0:
        raise file.error(where, "a water depth > 0 [m]", f"{depth:g}")
    return depth


def _positive(file: _File, where: str, what: str) -> float:
    value = file.scalar(where, what)
    if value <= 0.0:
        raise file.error(where, f"a {what} > 0", f"{value:g}")
    return value


def _excitation_part(file: _File, base: str, shape: tuple[int, ...], name: str
                     ) -> tuple[NDArray[np.complex128] | None, str | None]:
    """(re + i im) of an optional excitation part, or None with the reason when absent."""
    re_path, im_path = base + "/re", base + "/im"
    if not file.has(re_path) and not file.has(im_path):
        return None, f"no {name} part in the file"
    parts = [file.float_array(where, what, shape) for where, what in (
        (re_path, f"real part of the {name} force"),
        (im_path, f"imaginary part of the {name} force"))]
    if np.all(np.isnan(parts[0])) and np.all(np.isnan(parts[1])):
        # BEMIO's readWAMIT fills the parts with NaN when the run has no .3fk / .3sc.
        return None, f"the {name} part is all NaN in the file (BEMIO's mark for not computed)"
    file.finite(re_path, parts[0])
    file.finite(im_path, parts[1])
    return parts[0] + 1j * parts[1], None


def read_bemio(path: str | Path, *, body: int | None = None,
               water_density: float | None = None) -> ImportedBem:
    """Read one rigid body of a WEC-Sim BEMIO ``.h5`` file.

    Parameters
    ----------
    path
        The ``.h5`` file.
    body
        The body number (1-based, BEMIO's ``bodyN``); default: the file's only body.
    water_density
        rho [kg/m^3] to make the normalised values dimensional instead of the file's
        ``rho`` (BEMIO's values are divided by rho, which the potential-flow solution is
        proportional to; BEMIO's readWAMIT records 1000 whatever the run's density).

    Returns
    -------
    ImportedBem
        Dimensional SI values in floatmoor's layout and e^{-i omega t} convention, omega
        increasing, about the body's ``cg`` (the point WEC-Sim applies them at).

    Raises
    ------
    BemFileError
        The file is missing, not HDF5, or not a well-formed single-body selection of a
        BEMIO file (see the module).
    ValueError
        ``body`` < 1 or a non-positive ``water_density``.
    """
    import h5py

    name = str(path)
    if body is not None and (isinstance(body, bool) or int(body) != body or body < 1):
        raise ValueError(f"body must be an integer >= 1, got {body!r}")
    if water_density is not None and not (math.isfinite(water_density)
                                          and water_density > 0.0):
        raise ValueError(f"water_density must be a finite number > 0, got {water_density!r}")
    try:
        # opened here (regular, bounded, not blocking on a FIFO), then HDF5 reads this stream
        stream = open_regular(path, MAX_FILE_BYTES)
    except InputFileError as err:
        raise BemFileError(name, "", "a WEC-Sim BEMIO .h5 file (a regular file of at most "
                           f"{MAX_FILE_BYTES} bytes)", err.found) from None
    with stream:
        try:
            handle = h5py.File(stream, "r")
        except OSError as err:
            raise BemFileError(name, "", "an HDF5 file (WEC-Sim BEMIO .h5)",
                               f"a file HDF5 cannot open ({shown(err)})") from None
        with handle:
            try:
                return _read(_File(handle, name), body, water_density)
            except (OSError, RuntimeError, KeyError) as err:
                # HDF5's own failures on a damaged file (a truncated object header, a broken
                # B-tree), met while walking it: one line, not a traceback
                raise BemFileError(name, "", "a readable WEC-Sim BEMIO .h5 file",
                                   f"a damaged HDF5 file ({shown(err)})") from None


def _read(file: _File, body: int | None, water_density: float | None) -> ImportedBem:
    numbers = _bodies(file)
    if body is None:
        if len(numbers) > 1:
            names = {n: (file.text(f"/body{n}/properties/name", "body name")
                         if file.has(f"/body{n}/properties/name") else "") for n in numbers}
            listed = shown(", ".join(f"{n} '{names[n]}'" for n in numbers))
            raise file.error("", f"a body number (the file has {len(numbers)} bodies: "
                             f"{listed})", "none given")
        body = 1
    if body not in numbers:
        raise file.error(f"/body{body}", f"one of the file's bodies 1..{len(numbers)}",
                         f"body {body}")
    notes: list[str] = []
    sim = "/simulation_parameters/"
    scaled = file.scalar(sim + "scaled", "scaled flag")
    if scaled != 0.0:
        raise file.error(sim + "scaled", "0 (coefficients normalised by rho and g, as "
                         "writeBEMIOH5 writes them)", f"{scaled:g}")
    omega_file = file.vector(sim + "w", "wave frequencies [rad/s]")
    n_freq = omega_file.size
    if n_freq < 2:
        raise file.error(sim + "w", "at least 2 wave frequencies", f"{n_freq}")
    if np.any(omega_file <= 0.0):
        k = int(np.argmax(omega_file <= 0.0))
        raise file.error(sim + "w", "frequencies > 0 [rad/s]",
                         f"{omega_file[k]:g} at index {k}")
    periods = file.vector(sim + "T", "wave periods [s]", n_freq)
    mismatch = np.abs(periods * omega_file / (2.0 * math.pi) - 1.0)
    if np.any(mismatch > PERIOD_RTOL):
        k = int(np.argmax(mismatch))
        raise file.error(sim + "T", "the periods 2 pi / w",
                         f"T = {periods[k]:g} s at index {k} for w = {omega_file[k]:g} "
                         f"rad/s (2 pi / w = {2 * math.pi / omega_file[k]:g} s)")
    order = np.argsort(omega_file, kind="stable")
    omega = omega_file[order]
    repeated = np.flatnonzero(np.diff(omega) == 0.0)
    if repeated.size:
        raise file.error(sim + "w", "distinct frequencies",
                         f"{omega[repeated[0]]:g} rad/s more than once")
    if np.any(np.diff(order) < 0):
        notes.append("Frequencies sorted increasing (the file's were not).")

    dir_path = sim + "wave_dir"
    directions = file.vector(dir_path, "wave directions")
    units = file.attribute_text(file.raw(dir_path, "wave directions"), dir_path, "units",
                                "deg")
    if units.strip().lower() in ("rad", "radian", "radians"):
        directions_rad = directions.copy()
    elif units.strip().lower() in ("deg", "degree", "degrees", ""):
        directions_rad = np.radians(directions)
    else:
        raise file.error(dir_path, "units 'deg' or 'rad' (attribute 'units')",
                         f"'{shown(units)}'")
    n_dir = directions.size
    if n_dir < 1:
        raise file.error(dir_path, "at least 1 wave direction", "none")
    if np.unique(directions).size != n_dir:
        raise file.error(dir_path, "distinct wave directions",
                         shown(", ".join(f"{d:g}" for d in directions)))
    dir_order = np.argsort(directions_rad, kind="stable")

    rho_file = _positive(file, sim + "rho", "water density [kg/m^3]")
    g = _positive(file, sim + "g", "gravity [m/s^2]")
    depth = _water_depth(file)
    rho = rho_file if water_density is None else float(water_density)
    code = file.text("/bem_data/code", "BEM code") if file.has("/bem_data/code") else ""

    dofs = {n: _dof_range(file, n) for n in numbers}
    n_cols = sum(d for d, _, _ in dofs.values())
    dof, first, end = dofs[body]
    if dof != _N_DOF:
        raise file.error(f"/body{body}/properties/dof", "6 rigid-body DOFs (generalized body "
                         "modes are not supported)", f"{dof}")
    base = f"/body{body}/"
    props = base + "properties/"
    coeffs = base + "hydro_coeffs/"
    body_name = file.text(props + "name", "body name")
    file.scalar(props + "body_number", "body number")
    cg = file.vector(props + "cg", "centre of gravity [m]", 3)
    cb = file.vector(props + "cb", "centre of buoyancy [m]", 3)
    volume = file.scalar(props + "disp_vol", "displaced volume [m^3]")
    if volume < 0.0:
        raise file.error(props + "disp_vol", "a displaced volume >= 0 [m^3]", f"{volume:g}")

    stiffness = file.array(coeffs + "linear_restoring_stiffness",
                           "hydrostatic stiffness / (rho g)", (_N_DOF, _N_DOF))
    a_all = file.array(coeffs + "added_mass/all", "added mass / rho",
                       (_N_DOF, n_cols, n_freq))
    a_inf = file.array(coeffs + "added_mass/inf_freq", "infinite-frequency added mass / rho",
                       (_N_DOF, n_cols))
    b_all = file.array(coeffs + "radiation_damping/all", "radiation damping / (rho omega)",
                       (_N_DOF, n_cols, n_freq))
    exc_shape = (_N_DOF, n_dir, n_freq)
    ex_re = file.array(coeffs + "excitation/re", "real part of the excitation / (rho g)",
                       exc_shape)
    ex_im = file.array(coeffs + "excitation/im", "imaginary part of the excitation / (rho g)",
                       exc_shape)
    fk, fk_note = _excitation_part(file, coeffs + "excitation/froude-krylov", exc_shape,
                                   "Froude-Krylov")
    sc, sc_note = _excitation_part(file, coeffs + "excitation/scattering", exc_shape,
                                   "scattering")
    total = ex_re + 1j * ex_im
    if fk is not None and sc is not None:
        scale = np.max(np.abs(total), axis=(1, 2))[:, None, None]
        worst = np.abs(fk + sc - total) - PARTS_SUM_RTOL * scale
        if np.any(worst > 0.0):
            i, h, f = np.unravel_index(int(np.argmax(worst)), worst.shape)
            raise file.error(coeffs + "excitation/re, im",
                             f"froude-krylov + scattering (within {PARTS_SUM_RTOL:g} of the "
                             "DOF's largest value)",
                             f"{total[i, h, f]:.6g} against {fk[i, h, f] + sc[i, h, f]:.6g} "
                             f"at index [{i}, {h}, {f}]")
    elif fk is not None:
        sc, sc_note = total - fk, "scattering part = excitation - froude-krylov"
    elif sc is not None:
        fk, fk_note = total - sc, "Froude-Krylov part = excitation - scattering"
    for note in (fk_note, sc_note):
        if note:
            notes.append(note[0].upper() + note[1:] + ".")

    if len(numbers) > 1:
        others = [n for n in numbers if n != body]
        mask = np.ones(n_cols, dtype=bool)
        mask[first:end] = False
        own = np.max(np.abs(a_all[:, first:end, :]))
        dropped = np.max(np.abs(a_all[:, mask, :])) if mask.any() else 0.0
        share = f"{dropped / own:.3g}" if own > 0.0 else "n/a"
        notes.append(f"Body {body} of {len(numbers)}: its coupling with "
                     f"{'body' if len(others) == 1 else 'bodies'} "
                     f"{', '.join(map(str, others))} (added mass and damping per their "
                     f"motions) dropped; the largest dropped |A| is {share} of the body's "
                     "own largest.")

    def freq_last_to_first(values: NDArray[Any]) -> NDArray[Any]:
        """(i, j or direction, f) in the file -> (f sorted, j or direction, i)."""
        return np.transpose(values, (2, 1, 0))[order]

    added_mass = freq_last_to_first(a_all[:, first:end, :]) * rho
    damping = freq_last_to_first(b_all[:, first:end, :]) * rho * omega[:, None, None]
    a_infinite = a_inf[:, first:end].T * rho
    rho_g = rho * g

    def excitation(values: NDArray[np.complex128] | None) -> NDArray[np.complex128] | None:
        if values is None:
            return None
        # BEMIO's e^{+i omega t} amplitudes -> floatmoor's e^{-i omega t}: conjugate.
        return np.conj(freq_last_to_first(values))[:, dir_order, :] * rho_g

    if volume == 0.0:
        notes.append("disp_vol = 0 in the file (BEMIO writes 0 when the BEM run gave no "
                     "hydrostatics): displaced volume and centre of buoyancy not used.")
    if code.upper() != "WAMIT":
        notes.append(f"added_mass/inf_freq of a {shown(code, 80) or 'non-WAMIT'} run is "
                     "BEMIO's estimate (radiationIRF, or A at the highest frequency), not a "
                     "BEM solution at omega = infinity.")
    else:
        notes.append("BEMIO's readWAMIT takes WAMIT's values as normalised with ULEN = 1 and "
                     "records rho = 1000 kg/m^3 whatever the run's density.")
    notes.append("Hydrostatic stiffness: linear_restoring_stiffness x rho g as in the file, "
                 "the buoyancy part only when the BEM run's centre of gravity was its "
                 "reference point (WEC-Sim's convention: coefficients about cg).")
    notes.append("Rotation centre = the body's cg, the point WEC-Sim applies the "
                 "coefficients at.")
    notes.append(f"Dimensional with rho = {rho:g} kg/m^3"
                 + (f" (given; the file says {rho_file:g})" if water_density is not None
                    else " (the file's)") + f", g = {g:g} m/s^2 (the file's).")
    in_radians = units.strip().lower().startswith("rad")
    notes.append(f"Wave directions in {'radians' if in_radians else 'degrees'} in the file "
                 "(propagation directions); excitation conjugated (BEMIO's e^{+i omega t}).")

    second = read_bemio_mean_drift(file, body, exc_shape, order, dir_order, rho_g)
    return ImportedBem(
        format="bemio", files=(file.name,), omega=omega, added_mass=added_mass,
        radiation_damping=damping, water_density=rho, gravity=g,
        added_mass_infinite=a_infinite, added_mass_zero=None,
        directions=directions_rad[dir_order], excitation_force=excitation(total),
        froude_krylov_force=excitation(fk), diffraction_force=excitation(sc),
        hydrostatic_stiffness=stiffness * rho_g,
        disp_volume=volume if volume > 0.0 else None,
        center_of_buoyancy=cb if volume > 0.0 else None, center_of_gravity=cg,
        rotation_center=cg.copy(), water_depth=depth, body_name=body_name or None,
        notes=tuple(notes), second_order=second)
