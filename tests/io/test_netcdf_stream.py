"""The streamed netCDF-3 writer (floatmoor/io/netcdf_stream.py) and the lazy reader
(floatmoor/io/netcdf3_reader.py): against xarray's own writer and reader, killed between
writing records and counting them, attributes updated in place, read while it is written."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
import xarray as xr

from floatmoor.io import netcdf3_reader, netcdf_stream
from floatmoor.io.netcdf3_format import NUMRECS_OFFSET, NetCDF3Error, parse_header
from floatmoor.io.netcdf3_reader import open_netcdf3, read_attributes_netcdf3
from floatmoor.io.netcdf_stream import NetCDF3Stream
from tests.conftest import REPO

ENGINE, FORMAT = "scipy", "NETCDF3_64BIT"


def _dataset(n: int, first: int = 0) -> xr.Dataset:
    """A dataset like a run's: text coordinates, float and int series along time (first),
    a fixed variable, NaN in a series, text and number attributes."""
    t = np.arange(first, first + n) * 0.5
    k = np.arange(first, first + n)
    tension = np.stack([np.sin(t), np.cos(t)], axis=1) + k[:, None] * 1e-3
    tension[k == 3] = np.nan
    return xr.Dataset(
        {"tension": (("time", "line"), tension, {"units": "N", "long_name": "tension"}),
         "force": (("time", "line", "component"), np.repeat(tension[..., None], 3, axis=2),
                   {"units": "N", "long_name": "force"}),
         "iterations": (("time", "line"), np.stack([k, 2 * k], 1).astype(np.int32),
                        {"units": "1", "long_name": "iterations"}),
         "mbl": (("line",), np.array([1e6, np.nan]), {"units": "N", "long_name": "MBL"})},
        coords={"time": ("time", t, {"units": "s", "long_name": "time"}),
                "line": ("line", np.array(["l1", "line2"]), {"units": "1", "long_name": "line"}),
                "component": ("component", np.array(["x", "y", "z"]),
                              {"units": "1", "long_name": "axis"}),
                "model": ("line", np.array(["dynamic", "quasi-static"]),
                          {"units": "1", "long_name": "model"})},
        attrs={"title": "streamed", "status": "running", "wall_time_s": 0.0,
               "simulated_time_s": 0.0, "case_toml": "x = 1\n" * 50})


def _template(ds: xr.Dataset) -> bytes:
    return bytes(ds.to_netcdf(engine=ENGINE, format=FORMAT, unlimited_dims=["time"]))


def _records(stream: NetCDF3Stream, ds: xr.Dataset) -> dict[str, np.ndarray]:
    return {v.name: ds[v.name].values for v in stream.header.record_variables}


def _read(path) -> xr.Dataset:
    with xr.open_dataset(path, engine=ENGINE) as ds:
        return ds.load()


def test_appended_file_equals_xarrays_own(tmp_path):
    whole = _dataset(23)
    reference = tmp_path / "xarray.nc"
    whole.to_netcdf(reference, engine=ENGINE, format=FORMAT, unlimited_dims=["time"])
    out = tmp_path / "streamed.nc"
    with NetCDF3Stream.create(out, _template(whole.isel(time=slice(0, 5))),
                              reserve={"status": 64}) as stream:
        for a, b in ((5, 6), (6, 15), (15, 23)):
            stream.append(_records(stream, whole.isel(time=slice(a, b))))
        assert stream.numrecs == 23
    ours, theirs = _read(out), _read(reference)
    xr.testing.assert_identical(ours, theirs)
    assert ours.encoding["unlimited_dims"] == {"time"}
    assert np.isnan(ours["tension"].values[3]).all()
    # the same header as xarray's but for the status's room: names, types, attributes
    a, b = parse_header(out.read_bytes()), parse_header(reference.read_bytes())
    assert a.dims == b.dims and a.numrecs == b.numrecs == 23
    def described(header):
        return [(v.name, v.dim_ids, v.nc_type, [(x.name, x.nc_type, x.raw) for x in v.attributes])
                for v in header.variables]

    assert described(a) == described(b)
    assert [(x.name, x.raw) for x in a.attributes if x.name != "status"] == \
        [(x.name, x.raw) for x in b.attributes if x.name != "status"]
    assert a.attribute("status").raw == b"running".ljust(64, b"\x00")


def test_lazy_reader_gives_the_scipy_engines_dataset(tmp_path, monkeypatch):
    monkeypatch.setattr(netcdf3_reader, "BLOCK_BYTES", 100)  # a few records a block
    path = tmp_path / "a.nc"
    _dataset(40).to_netcdf(path, engine=ENGINE, format=FORMAT, unlimited_dims=["time"])
    theirs = _read(path)
    with open_netcdf3(path) as ours:
        assert ours["tension"].variable._in_memory is False  # nothing read yet
        for key in ({"time": slice(None, None, -3)}, {"time": 7, "line": 1},
                    {"time": slice(35, 2, -5), "component": 2}, {"time": [9, 2, 30]}):
            xr.testing.assert_identical(ours.isel(key).load(), theirs.isel(key))
        xr.testing.assert_identical(ours.load(), theirs)
        for name, var in theirs.variables.items():
            assert ours[name].dtype == var.dtype
            assert {k: type(v) for k, v in ours[name].attrs.items()} == \
                {k: type(v) for k, v in var.attrs.items()}
    assert read_attributes_netcdf3(path) == theirs.attrs
    # record variables presented with their second dimension first, read as such
    with open_netcdf3(path, record_second=("line",)) as ours:
        assert ours["tension"].dims == ("line", "time")
        assert ours["force"].dims == ("line", "time", "component")
        swapped = theirs.transpose("line", "time", ...)
        for key in ({"time": slice(None, None, -3)}, {"time": 7, "line": 1}, {"line": 0},
                    {"time": slice(35, 2, -5), "component": 2}, {"line": slice(None, None, -1)}):
            xr.testing.assert_identical(ours.isel(key).load(), swapped.isel(key))
    # a fixed-size file too
    fixed = tmp_path / "fixed.nc"
    _dataset(4).to_netcdf(fixed, engine=ENGINE, format=FORMAT)
    with open_netcdf3(fixed) as ours:
        xr.testing.assert_identical(ours.load(), _read(fixed))


def test_killed_before_counting_the_records_keeps_the_earlier_ones(tmp_path, monkeypatch):
    """The records are written after the last one, then counted: a write that fails (or a
    process killed) in between leaves the file with its earlier records, valid."""
    whole = _dataset(12)
    out = tmp_path / "r.nc"
    stream = NetCDF3Stream.create(out, _template(whole.isel(time=slice(0, 4))))
    real = netcdf_stream._write_all

    def dies_at_the_count(fd, data, offset):
        if offset == NUMRECS_OFFSET:
            raise OSError(28, "No space left on device")
        real(fd, data, offset)

    monkeypatch.setattr(netcdf_stream, "_write_all", dies_at_the_count)
    with pytest.raises(netcdf_stream.OutputWriteError, match="No space left on device"):
        stream.append(_records(stream, whole.isel(time=slice(4, 9))))
    size = out.stat().st_size
    partial = _read(out)
    assert partial.sizes["time"] == 4  # the appended records are beyond the count
    xr.testing.assert_identical(partial, whole.isel(time=slice(0, 4)).pipe(
        lambda d: _read_back(d, tmp_path)))
    # cut inside the uncounted records (a kill mid-write): still the same valid file
    os.truncate(out, size - 37)
    assert _read(out).sizes["time"] == 4
    monkeypatch.setattr(netcdf_stream, "_write_all", real)
    stream.close()
    with NetCDF3Stream.open(out) as again:  # and it can be continued
        again.append(_records(again, whole.isel(time=slice(4, 12))))
    xr.testing.assert_identical(_read(out), _read_back(whole, tmp_path))


def test_records_failing_to_be_written_are_not_counted(tmp_path, monkeypatch):
    whole = _dataset(9)
    out = tmp_path / "r.nc"
    stream = NetCDF3Stream.create(out, _template(whole.isel(time=slice(0, 4))))
    real = netcdf_stream._write_all
    end = out.stat().st_size

    def disk_full_at_the_records(fd, data, offset):
        if offset == end:
            real(fd, bytes(data)[:10], offset)  # a few bytes, then the disk is full
            raise OSError(28, "No space left on device")
        real(fd, data, offset)

    monkeypatch.setattr(netcdf_stream, "_write_all", disk_full_at_the_records)
    with pytest.raises(netcdf_stream.OutputWriteError):
        stream.append(_records(stream, whole.isel(time=slice(4, 9))))
    assert stream.numrecs == 4 and _read(out).sizes["time"] == 4
    stream.close()


def _read_back(ds: xr.Dataset, folder) -> xr.Dataset:
    """``ds`` as xarray writes and reads it (a record file)."""
    path = folder / f"ref-{ds.sizes['time']}.nc"
    ds.to_netcdf(path, engine=ENGINE, format=FORMAT, unlimited_dims=["time"])
    return _read(path)


def test_a_file_whose_count_exceeds_its_records_is_refused(tmp_path):
    """The opposite order (counted before written) would leave such a file: it is damaged."""
    path = tmp_path / "a.nc"
    _dataset(6).to_netcdf(path, engine=ENGINE, format=FORMAT, unlimited_dims=["time"])
    os.truncate(path, path.stat().st_size - 8)
    with pytest.raises(NetCDF3Error, match="truncated"):
        open_netcdf3(path)
    with pytest.raises(NetCDF3Error, match="truncated"):
        NetCDF3Stream.open(path)
    with pytest.raises(NetCDF3Error, match="truncated"):
        parse_header(path.read_bytes()[:40])


def test_attributes_are_updated_in_place_or_with_more_room(tmp_path):
    ds = _dataset(3)
    out = tmp_path / "r.nc"
    stream = NetCDF3Stream.create(out, _template(ds), reserve={"status": 32})
    inode = out.stat().st_ino
    stream.set_attributes({"status": "failed: é", "wall_time_s": 12.5,
                           "simulated_time_s": 1.0})
    attrs = _read(out).attrs
    assert attrs["status"] == "failed: é" and attrs["wall_time_s"] == 12.5
    assert attrs["simulated_time_s"] == 1.0 and out.stat().st_ino == inode  # in place
    long = "failed: " + "a very long message " * 20
    stream.set_attributes({"status": long})  # beyond the room: the file is rewritten
    stream.append(_records(stream, _dataset(2, first=3)))
    stream.set_attributes({"status": "complete"})
    stream.close()
    back = _read(out)
    assert back.attrs["status"] == "complete" and back.sizes["time"] == 5
    xr.testing.assert_identical(back.drop_attrs(), _read_back(_dataset(5), tmp_path).drop_attrs())
    assert back.attrs["case_toml"] == ds.attrs["case_toml"]
    assert not list(tmp_path.glob(".*.tmp"))
    with NetCDF3Stream.open(out) as again:
        with pytest.raises(KeyError):
            again.set_attributes({"missing": "x"})
        with pytest.raises(ValueError, match="holds text"):
            again.set_attributes({"status": 3.0})
        with pytest.raises(ValueError, match="number"):
            again.set_attributes({"wall_time_s": "x"})


def test_file_is_readable_while_it_is_written(tmp_path):
    whole = _dataset(30)
    out = tmp_path / "r.nc"
    with NetCDF3Stream.create(out, _template(whole.isel(time=slice(0, 1)))) as stream:
        for n in range(1, 30, 7):
            seen = _read(out)  # another reader, the writer still open
            assert seen.sizes["time"] == n
            np.testing.assert_array_equal(seen["iterations"].values,
                                          whole["iterations"].values[:n])
            stream.append(_records(stream, whole.isel(time=slice(n, min(n + 7, 30)))))
    assert _read(out).sizes["time"] == 30


def test_values_that_xarray_would_transform_are_refused(tmp_path):
    ds = _dataset(3)
    packed = ds.copy()
    packed["tension"].encoding.update(scale_factor=0.5, dtype="int16", _FillValue=-1)
    with pytest.raises(NetCDF3Error, match="scale_factor"):
        NetCDF3Stream.create(tmp_path / "a.nc", _template(packed))
    with pytest.raises(NetCDF3Error, match="record"):
        NetCDF3Stream.create(tmp_path / "b.nc", bytes(ds.to_netcdf(engine=ENGINE,
                                                                   format=FORMAT)))
    with NetCDF3Stream.create(tmp_path / "c.nc", _template(ds)) as stream:
        records = _records(stream, _dataset(2, first=3))
        records["iterations"] = records["iterations"].astype(np.float64)  # would lose
        with pytest.raises(TypeError):
            stream.append(records)
        del records["iterations"]
        with pytest.raises(ValueError, match="iterations"):
            stream.append(records)
        assert stream.numrecs == 3
    assert not list(tmp_path.glob("[ab].nc"))


_KILLED_WRITER = textwrap.dedent("""
    import sys
    import numpy as np
    sys.path.insert(0, sys.argv[2])
    from tests.io.test_netcdf_stream import _dataset, _records, _template
    from floatmoor.io.netcdf_stream import NetCDF3Stream
    stream = NetCDF3Stream.create(sys.argv[1], _template(_dataset(1)))
    print("ready", flush=True)
    n = 1
    while True:
        stream.append(_records(stream, _dataset(50, first=n)))
        stream.set_attributes({"simulated_time_s": float(n)})
        n += 50
""")


def test_file_of_a_writer_killed_at_any_moment_is_valid(tmp_path):
    """SIGKILL at random moments of a writer appending as fast as it can: the file is
    readable, its records all written and in order."""
    rng = np.random.default_rng(17)
    for attempt in range(4):
        out = tmp_path / f"k{attempt}.nc"
        child = subprocess.Popen([sys.executable, "-c", _KILLED_WRITER, str(out), str(REPO)],
                                 stdout=subprocess.PIPE, text=True)
        assert child.stdout.readline().strip() == "ready"
        time.sleep(rng.uniform(0.05, 0.4))
        child.send_signal(signal.SIGKILL)
        child.wait()
        ds = _read(out)
        n = ds.sizes["time"]
        assert n >= 1
        np.testing.assert_array_equal(ds["iterations"].values[:, 0], np.arange(n))
        np.testing.assert_array_equal(ds["time"].values, np.arange(n) * 0.5)
