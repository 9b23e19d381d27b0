"""floatmoor.input_files and file_sha256: only regular files are read, without blocking
on a FIFO, within a size limit; what a path is instead is said in one phrase."""

from __future__ import annotations

import os

import pytest

from floatmoor.file_hash import file_sha256
from floatmoor.input_files import InputFileError, open_regular, read_bounded


def test_kinds_of_paths_are_named(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    zero = tmp_path / "zero"
    zero.symlink_to("/dev/zero")
    for path, found in ((fifo, "a FIFO (named pipe), not a regular file"),
                        (zero, "a character device, not a regular file"),
                        (tmp_path, "a folder, not a regular file"),
                        (tmp_path / "none", "no such file")):
        with pytest.raises(InputFileError) as info:
            open_regular(path)
        assert info.value.found == found and info.value.strerror == found


def test_sizes_are_bounded_before_reading(tmp_path):
    path = tmp_path / "f.bin"
    path.write_bytes(b"x" * 10)
    assert read_bounded(path, 10) == b"x" * 10
    with pytest.raises(InputFileError, match="a file of 10 bytes, more than the 9 bytes read"):
        read_bounded(path, 9)
    assert file_sha256(path, size=10) == file_sha256(path)
    with pytest.raises(OSError, match="more than the 9 bytes"):
        file_sha256(path, size=9)
    with pytest.raises(OSError, match="a file of 10 bytes, not the 11 bytes expected"):
        file_sha256(path, size=11)
    with pytest.raises(InputFileError, match="FIFO"):
        os.mkfifo(tmp_path / "pipe")
        file_sha256(tmp_path / "pipe")
