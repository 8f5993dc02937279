"""Opening an archive that may have been crafted: no local file read, no huge allocation.

An HDF5 file can point outside itself: external links (``ExternalLink`` to another file),
soft links, external raw storage (``Dataset.external``: the data bytes live in any local
file), virtual datasets (``Dataset.is_virtual``: mapped from other files) and object or
region references. It can also declare a dataset of terabytes that compresses to a few
bytes, or a table whose columns disagree on their length. :func:`open_campaign` walks the
whole file once, before any data is read, and refuses all of these with one line
(:class:`~rockscreen.pipeline.errors.ArchiveError`); :func:`read_column` and :func:`read_table`
check shapes and dtypes before reading (the tables of an archive kind:
:func:`rockscreen.pipeline.archive.table_checks.check_tables`); :func:`reading` turns
any other failure of the HDF5 library while reading into one line too.
"""

from __future__ import annotations

import contextlib
import json
import os
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.schema import FORMAT, SUPPORTED_VERSIONS, check_format
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

__all__ = [
    "MAX_ATTRIBUTE_BYTES",
    "MAX_DATASET_BYTES",
    "MAX_ROWS",
    "check_attribute_sizes",
    "check_tree",
    "closed_on_failure",
    "code_table",
    "decode_codes",
    "open_campaign",
    "open_hdf5",
    "read_column",
    "read_table",
    "reading",
]

#: Largest dataset a reader accepts, in bytes of its in-memory array (2 GiB): far above
#: the history arrays of a 10,000-tower campaign (~80 MB), far below what a crafted
#: file can declare (terabytes of zeros compress to a few bytes).
MAX_DATASET_BYTES = 2 * 1024**3
#: Largest row count of a text (variable-length) column.
MAX_ROWS = 50_000_000
#: Largest attribute, in bytes (a resolved configuration is a few kB).
MAX_ATTRIBUTE_BYTES = 16 * 1024**2
# HDF5 filters a rockscreen archive may use: deflate, shuffle, fletcher32, szip, nbit,
# scale-offset (built into libhdf5) and LZF (built into h5py). Any other id would load
# a plugin library from HDF5_PLUGIN_PATH.
_FILTERS = frozenset({1, 2, 3, 4, 5, 6, 32000})
# SystemError: h5py's lock re-raises an HDF5 failure inside a visit callback as one.
_EXPECTED_ERRORS = (
    OSError,
    KeyError,
    ValueError,
    TypeError,
    IndexError,
    RuntimeError,
    SystemError,
)


def _name(path: Any) -> str:
    return printable(os.fspath(path))


def _dtype_problem(dtype: np.dtype) -> str | None:
    """Return why a dtype is not allowed in an archive, or None."""
    if h5py.check_string_dtype(dtype) is not None:
        return None
    if h5py.check_ref_dtype(dtype) is not None:
        return "holds object or region references"
    if dtype.kind in "biuf" and dtype.shape == ():
        return None
    if dtype.kind == "S" and dtype.shape == ():
        return None
    return f"has a dtype rockscreen never writes ({printable(str(dtype))[:40]})"


def _dataset_problem(ds: h5py.Dataset) -> str | None:
    """Return why a dataset must not be read, or None."""
    if ds.is_virtual:
        return "is a virtual dataset (mapped from other files)"
    if ds.external:
        return "stores its data in external files"
    if ds.dtype.names and ds.name == "/cases":
        # The one compound table rockscreen writes (a sweep's cases): every field must pass.
        fields = [ds.dtype.fields[name][0] for name in ds.dtype.names]
        problem = next((p for p in map(_dtype_problem, fields) if p), None)
    else:
        problem = _dtype_problem(ds.dtype)
    if problem:
        return problem
    shape = ds.shape or ()
    if shape is None or len(shape) > 2:
        return f"has {len(shape)} dimensions"
    n = int(np.prod(shape, dtype=np.float64)) if shape else 1
    if n * max(ds.dtype.itemsize, 1) > MAX_DATASET_BYTES:
        gib = n * ds.dtype.itemsize / 1024**3
        return f"declares {gib:.3g} GiB (limit {MAX_DATASET_BYTES // 1024**3} GiB)"
    if h5py.check_string_dtype(ds.dtype) is not None and n > MAX_ROWS:
        return f"declares {n} text cells (limit {MAX_ROWS})"
    plist = ds.id.get_create_plist()
    for i in range(plist.get_nfilters()):
        code = plist.get_filter(i)[0]
        if code not in _FILTERS:
            return f"uses HDF5 filter {code}, which rockscreen never writes"
    return None


def _attributes_problem(obj: Any) -> str | None:
    for key in obj.attrs:
        aid = obj.attrs.get_id(key)
        if (
            h5py.check_ref_dtype(aid.dtype) is not None
            or aid.dtype.hasobject
            and (h5py.check_string_dtype(aid.dtype) is None)
        ):
            return f"attribute {printable(key)[:40]!r} holds object or region references"
        size = int(np.prod(aid.shape or (), dtype=np.float64)) * max(aid.dtype.itemsize, 1)
        if size > MAX_ATTRIBUTE_BYTES:
            return f"attribute {printable(key)[:40]!r} is {size} bytes"
    return None


def check_tree(f: h5py.File, path: Any) -> None:
    """Walk every link of an open file once and refuse what could read outside it.

    Parameters
    ----------
    f : h5py.File
        The open file.
    path : str or path-like
        Its path, for messages.

    Raises
    ------
    ArchiveError
        On an external or soft link, a virtual dataset, external raw storage, a reference
        dtype, an unknown filter, an oversized dataset or attribute, or an object of a
        type rockscreen never writes.
    """
    problems: list[str] = []
    problem = _attributes_problem(f)
    if problem:
        problems.append(f"/: {problem}")

    def visit(name: str, link: Any) -> Any:
        if isinstance(link, h5py.ExternalLink):
            problems.append(f"/{name} is an external link to another file")
        elif isinstance(link, h5py.SoftLink):
            problems.append(f"/{name} is a soft link")
        elif not isinstance(link, h5py.HardLink):
            problems.append(f"/{name} is a link of an unknown kind")
        else:
            obj = f.get(name)
            if isinstance(obj, h5py.Dataset):
                issue = _dataset_problem(obj)
            elif isinstance(obj, h5py.Group):
                issue = None
            else:
                issue = "is an object rockscreen never writes (a named datatype?)"
            issue = issue or _attributes_problem(obj)
            if issue:
                problems.append(f"/{name} {issue}")
        return True if problems else None

    f.visititems_links(visit)
    if problems:
        raise ArchiveError(
            f"{_name(path)}: refused, /{printable(problems[0][1:])[:200]} "
            "(an archive must be self-contained, of the types and sizes rockscreen writes)"
        )


@contextlib.contextmanager
def reading(path: Any, what: str = "archive") -> Iterator[None]:
    """Turn any failure of the HDF5 library inside the block into one ArchiveError line."""
    try:
        yield
    except ArchiveError:
        raise
    except MemoryError as exc:
        raise ArchiveError(
            f"{_name(path)}: not enough memory to read the {what}; is it a crafted or damaged file?"
        ) from exc
    except _EXPECTED_ERRORS as exc:
        reason = printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
        raise ArchiveError(f"{_name(path)}: damaged or malformed {what} ({reason[:200]})") from exc


@contextlib.contextmanager
def closed_on_failure(f: h5py.File) -> Iterator[h5py.File]:
    """Close ``f`` when the block raises (the file is returned to the caller otherwise)."""
    try:
        yield f
    except BaseException:
        f.close()
        raise


def open_hdf5(path: Path, name: str) -> h5py.File:
    """Open a regular file read-only as HDF5, or refuse it with one line.

    Parameters
    ----------
    path : Path
        The archive.
    name : str
        How messages name it (printable).

    Returns
    -------
    h5py.File
        The open file (close it).

    Raises
    ------
    ArchiveError
        A missing file, one that is not a regular file (a FIFO or a device would block the
        open) or not readable HDF5 (the library's first line of the reason).
    """
    if not path.is_file():
        if path.exists():
            raise ArchiveError(f"archive {name!r} is not a regular file")
        raise ArchiveError(f"archive {name!r} does not exist")
    try:
        return h5py.File(path, "r")
    except (OSError, ValueError, RuntimeError, SystemError) as exc:
        reason = printable(str(exc).splitlines()[0] if str(exc) else "")[:200]
        raise ArchiveError(f"{name!r} is not a readable HDF5 file: {reason}") from exc


def open_campaign(
    path: str | os.PathLike,
    kinds: Iterable[str] = (FORMAT,),
    versions: Iterable[str] = SUPPORTED_VERSIONS,
) -> tuple[h5py.File, str]:
    """Open an archive for reading, after checking its format, version and whole tree.

    Parameters
    ----------
    path : str or path-like
        The archive.
    kinds, versions : iterable of str
        Accepted ``format`` and ``format_version`` (see
        :func:`rockscreen.pipeline.archive.schema.check_format`).

    Returns
    -------
    (h5py.File, str)
        The open file (close it) and its format version.

    Raises
    ------
    ArchiveError
        One line: missing file, not HDF5, not a rockscreen archive, unsupported version,
        or a refused tree (:func:`check_tree`).
    """
    path = Path(path)
    f = open_hdf5(path, _name(path))
    with closed_on_failure(f):
        version = check_format(f, path, kinds, versions)
        with reading(path):
            check_tree(f, path)
    return f, version


def read_column(ds: Any, path: Any, name: str, rows: int | None = None) -> np.ndarray:
    """Read one 1-D column after checking its type and length; text comes back as ``str``.

    Parameters
    ----------
    ds : h5py.Dataset or other
        The column (anything else is refused).
    path : str or path-like
        The archive, for messages.
    name : str
        The column's name in the archive, for messages.
    rows : int, optional
        The row count it must have.

    Returns
    -------
    numpy.ndarray
        Numbers as stored; text as an object array of ``str``.

    Raises
    ------
    ArchiveError
        If it is not a 1-D dataset of numbers or text of the expected length.
    """
    if not isinstance(ds, h5py.Dataset):
        raise ArchiveError(f"{_name(path)}: /{printable(name)} is not a dataset")
    if ds.ndim != 1:
        raise ArchiveError(
            f"{_name(path)}: /{printable(name)} has shape {ds.shape}; a table column is 1-D"
        )
    if rows is not None and ds.shape[0] != rows:
        raise ArchiveError(
            f"{_name(path)}: /{printable(name)} has {ds.shape[0]} rows where its table has {rows}"
        )
    problem = _dataset_problem(ds)
    if problem:
        raise ArchiveError(f"{_name(path)}: /{printable(name)} {problem}")
    with reading(path):
        if h5py.check_string_dtype(ds.dtype) is not None or ds.dtype.kind == "S":
            return np.asarray(ds.asstr(errors="replace")[:], dtype=object)
        if "codes" in ds.attrs:
            return decode_codes(ds, path, name)
        return ds[:]


def code_table(ds: h5py.Dataset, path: Any, name: str) -> list[str]:
    """Return the code table of a coded text column (its ``codes`` attribute), checked.

    Parameters
    ----------
    ds : h5py.Dataset
        A text column stored as unsigned integer codes
        (:func:`rockscreen.pipeline.archive.risk_archive.write_column`).
    path : str or path-like
        The archive, for messages.
    name : str
        The column's name in the archive, for messages.

    Returns
    -------
    list of str
        The values, by code.

    Raises
    ------
    ArchiveError
        When the codes are not unsigned integers or the attribute is not a JSON list of
        text (one line naming the file and the column).
    """
    raw = ds.attrs["codes"]
    try:
        codes = json.loads(raw.decode("utf-8") if isinstance(raw, bytes) else str(raw))
    except (ValueError, UnicodeDecodeError):
        codes = None
    if ds.dtype.kind != "u" or not (
        isinstance(codes, list) and all(isinstance(c, str) for c in codes)
    ):
        raise ArchiveError(
            f"{_name(path)}: /{printable(name)} is not a coded text column (unsigned codes "
            "and a 'codes' attribute holding the JSON list of its values)"
        )
    return codes


def decode_codes(ds: h5py.Dataset, path: Any, name: str) -> np.ndarray:
    """Return a coded text column's values (``codes[code]`` per row) as ``str`` objects.

    Raises
    ------
    ArchiveError
        For a malformed code table (:func:`code_table`) or a code outside it.
    """
    codes = code_table(ds, path, name)
    data = ds[:]
    if data.size and int(data.max()) >= len(codes):
        row = int(np.flatnonzero(data >= len(codes))[0])
        raise ArchiveError(
            f"{_name(path)}: /{printable(name)} row {row} holds code {int(data[row])}, "
            f"outside its code table of {len(codes)} value(s)"
        )
    values = np.empty(len(codes), dtype=object)
    values[:] = codes
    return values[data]


def read_table(group: Any, path: Any, n: int | None = None) -> dict[str, np.ndarray]:
    """Read every column of a table group, checking they all have the same length.

    Parameters
    ----------
    group : h5py.Group
        The table.
    path : str or path-like
        The archive, for messages.
    n : int, optional
        Keep only the first ``n`` rows (the committed rows of a work file).

    Returns
    -------
    dict of str to numpy.ndarray
        Column name -> values (text as ``str``).
    """
    if not isinstance(group, h5py.Group):
        raise ArchiveError(f"{_name(path)}: a table is missing or is not a group")
    names = list(group)
    rows = None
    out = {}
    for name in names:
        ds = group.get(name)
        full = f"{group.name.lstrip('/')}/{name}"
        if rows is None and isinstance(ds, h5py.Dataset) and ds.ndim == 1:
            rows = ds.shape[0]
        data = read_column(ds, path, full, rows)
        out[name] = data if n is None else data[:n]
    return out


@contextlib.contextmanager
def open_checked(path: str | os.PathLike) -> Iterator[h5py.File]:
    """Open any rockscreen archive (campaign, sweep, assess, scenario) after the tree check.

    For readers that dispatch on the archive's kind themselves (the HTML report): the
    file is refused, in one line, on an external or soft link, external or virtual
    storage, a reference or an oversized dataset (:func:`check_tree`), and any HDF5
    failure inside the block becomes one :class:`ArchiveError` line.

    Yields
    ------
    h5py.File
        The open file, closed when the block ends.
    """
    path = Path(path)
    if not path.is_file():
        raise ArchiveError(f"archive {_name(path)!r} is not a regular file")
    try:
        f = h5py.File(path, "r")
    except (OSError, ValueError, RuntimeError, SystemError) as exc:
        raise ArchiveError(f"{_name(path)!r} is not a readable HDF5 file") from exc
    with f, reading(path):
        check_tree(f, path)
        yield f


def check_attribute_sizes(f: h5py.File, path: Any) -> None:
    """Refuse a root attribute whose text is longer than :data:`MAX_ATTRIBUTE_BYTES`.

    :func:`check_tree` sizes an attribute by its declared shape and item size; a
    variable-length string declares a pointer's size whatever it holds. Its text lives in the
    file, so only a file larger than the limit can hold one too long: the root
    attributes of such a file are read and measured here.

    Parameters
    ----------
    f : h5py.File
        The open file.
    path : str or path-like
        Its path, for messages.

    Raises
    ------
    ArchiveError
        On a root attribute of more than :data:`MAX_ATTRIBUTE_BYTES` bytes of text.
    """
    try:
        size = os.path.getsize(f.filename)
    except OSError:
        size = MAX_ATTRIBUTE_BYTES + 1
    if size <= MAX_ATTRIBUTE_BYTES:
        return
    for key in f.attrs:
        aid = f.attrs.get_id(key)
        info = h5py.check_string_dtype(aid.dtype)
        if info is None or info.length is not None:  # fixed-length: check_tree sized it
            continue
        value = f.attrs[key]
        items = value.ravel() if isinstance(value, np.ndarray) else [value]
        length = sum(len(item) for item in items if isinstance(item, (str, bytes)))
        if length > MAX_ATTRIBUTE_BYTES:
            raise ArchiveError(
                f"{_name(path)}: refused, root attribute {printable(key)[:40]!r} holds "
                f"{length} bytes of text (limit {MAX_ATTRIBUTE_BYTES})"
            )
