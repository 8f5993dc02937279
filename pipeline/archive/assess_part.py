"""The work file of ``rockscreen assess`` (``OUT.part``): towers kept as they finish, resumed.

An assessment solves every tower for minutes; an interrupted one (Ctrl-C, ``kill``,
SIGTERM, a lost worker, a full disk) must not lose the towers already finished.
:class:`AssessJournal` keeps them in ``OUT.part`` beside the archive ``OUT``: the main
process appends each finished chunk of towers, records the committed tower count in a
root attribute and flushes, so a process killed at any moment leaves a file whose
committed towers are complete. Layout::

    /                 attrs: format="rockscreen-assess-part", part_version, fingerprint,
                      inputs (JSON: rockscreen version, inventory and suite content hashes
                      with their sources, the resolved options), committed, created_utc
    /towers/index     i8   the tower's position in the inventory
    /towers/id        str  the tower's id
    /towers/result    str  the tower's stripes, outcomes, IDA rows and summary row
                           (tagged JSON: :func:`.kept_rows.encode_result`, exact for
                           every float)
    /towers/sha256    str  SHA-256 of each result text (checked before a resume: a torn
                           write is caught, never resumed as a wrong tower)
    /towers/row       str  the tower's summary row alone (tagged JSON, as in its result):
                           what the archive's ``/summary`` reads back, a part at a time
                           (:meth:`AssessJournal.rows`), without decoding the whole result

The same command again resumes the file once a child process has read every committed
tower (:func:`rockscreen.pipeline.archive.resume.verify_assess_part`; a damaged file is
discarded with a warning, a file of other inputs is refused with the difference named
and kept, unless ``--overwrite``). Fresh and resumed towers both pass through
the codec of :mod:`rockscreen.pipeline.archive.kept_rows` (``encode_result``,
``decode_result``), so a resumed assessment writes the same archive as an uninterrupted
one. The main process keeps only each tower's summary row and counts (``light_result``);
its stripes, outcomes and IDA rows stay in the work file and the final archive's writer
reads them back :data:`READ_TOWERS` towers at a time (``kept_rows.JournalRows``), so its
memory grows with that part, not with the inventory. The
final archive is written by
:func:`rockscreen.pipeline.archive.risk_archive.write_risk_archive`; :meth:`AssessJournal.remove`
deletes the work file after it. The work file keeps no inventory: the archive's
``/inventory`` is written from the towers as read, which a resumed run reads again and
whose content the fingerprint holds (a work file of another inventory is not resumed).
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import math
import os
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.kept_rows import (
    decode_data,
    decode_result,
    encode_result,
    light_result,
)
from rockscreen.pipeline.archive.resume import (
    ASSESS_PART_FORMAT,
    NOT_AN_ASSESS_PART,
    PartFile,
    is_disk_full,
    is_hdf5,
    part_path,
    verify_assess_part,
)
from rockscreen.pipeline.archive.safety import reading
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

__all__ = [
    "PART_VERSION",
    "READ_TOWERS",
    "AssessJournal",
    "input_differences",
    "inputs_fingerprint",
    "part_path",
    "suite_digest",
]

#: Version of the work-file layout (a work file of another version is discarded, not
#: resumed). 2: a tower's screening risk keeps its ``survey_first`` input's groups
#: (``SurveyGroups``), not every sample's probability, weight and input.
#: 3: each tower's summary row also alone in ``/towers/row``.
PART_VERSION = "3"
#: Towers read back from the work file at a time (resumed towers, the archive's tables).
#: A part holds each of its towers' whole result text and decoded rows while one table is
#: written (about 0.3 MB a tower at one site per tower, measured: 198 outcome rows as
#: dicts): 32 towers, about 10 MB; 256 took about 75 MB more (issue 30, docs/scaling.md).
READ_TOWERS = 32
_STR = h5py.string_dtype("utf-8")
#: The work file's columns, one row per tower (module docstring).
_COLUMNS = ("index", "id", "result", "sha256", "row")
#: Input entries that name where an input came from: shown, not fingerprinted (a renamed
#: inventory of the same content resumes).
_SOURCE_KEY = "source"


def _part_version(part: os.PathLike | str) -> str:
    """Return a checked work file's ``part_version`` ("" when it has none or is unreadable)."""
    try:
        with h5py.File(part, "r") as f:
            value = f.attrs.get("part_version", "")
    except (OSError, RuntimeError):
        return ""
    return value.decode("utf-8", "replace") if isinstance(value, bytes) else str(value)


# ------------------------------------------------------------------------ inputs


def _fingerprinted(inputs: Any) -> Any:
    if isinstance(inputs, dict):
        return {k: _fingerprinted(v) for k, v in inputs.items() if k != _SOURCE_KEY}
    return inputs


def inputs_fingerprint(inputs: dict[str, Any]) -> str:
    """Return the SHA-256 of an assessment's inputs, their ``source`` entries left out.

    Parameters
    ----------
    inputs : dict
        JSON-ready description of everything that determines the towers' results: the
        rockscreen version, the inventory and suite content hashes, the resolved options.
        Entries named ``source`` (file names) are shown in messages, not fingerprinted.

    Returns
    -------
    str
        64 hexadecimal digits.
    """
    text = json.dumps(_fingerprinted(inputs), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _shown(value: Any) -> str:
    text = value if isinstance(value, str) else json.dumps(value, sort_keys=True)
    text = printable(text)
    return text if len(text) <= 60 else text[:57] + "..."


def input_differences(stored: dict[str, Any], current: dict[str, Any]) -> list[str]:
    """Name what differs between the inputs of a work file and those of this command.

    Parameters
    ----------
    stored, current : dict
        The inputs of the work file and of this command (as given to
        :func:`inputs_fingerprint`).

    Returns
    -------
    list of str
        One phrase per difference, e.g. ``"option n_records: 7 in the .part, 5 now"``,
        ``"inventory content (towers.csv)"``; empty when the fingerprints agree.
    """
    out = []
    for key in sorted(set(stored) | set(current)):
        old, new = stored.get(key), current.get(key)
        if _fingerprinted(old) == _fingerprinted(new):
            continue
        if isinstance(old, dict) and isinstance(new, dict) and "sha256" in new:
            source = new.get(_SOURCE_KEY) or old.get(_SOURCE_KEY) or ""
            out.append(f"{key} content ({_shown(source)})" if source else f"{key} content")
        elif isinstance(old, dict) and isinstance(new, dict):
            for name in sorted(set(old) | set(new)):
                if name == _SOURCE_KEY or old.get(name) == new.get(name):
                    continue
                out.append(
                    f"{key} {name}: {_shown(old.get(name, '(none)'))} in the .part, "
                    f"{_shown(new.get(name, '(none)'))} now"
                )
        else:
            out.append(f"{key}: {_shown(old)} in the .part, {_shown(new)} now")
    return out


# ------------------------------------------------------------------------ the journal


class AssessJournal(PartFile):
    """The towers of an assessment kept in ``OUT.part`` as they finish.

    Parameters
    ----------
    path : str or path-like
        The final archive ``OUT`` (the work file is ``OUT.part``).
    inputs : dict
        The assessment's inputs (:func:`inputs_fingerprint`).
    discard_other : bool
        Discard a work file of other inputs (``--overwrite``) instead of refusing.

    Attributes
    ----------
    fingerprint : str
        :func:`inputs_fingerprint` of ``inputs``.
    done : dict of int to dict
        Tower index -> its result without its table rows (:func:`light_result`: each a
        :class:`KeptRows`, read back by :meth:`tables`) nor its summary row (read back by
        :meth:`rows`), for the towers already in the work file.

    The rest (``part``, ``resumed``, ``discarded``, ``write_failed`` when an
    :meth:`append` failed, :meth:`remove`) is
    :class:`~rockscreen.pipeline.archive.resume.PartFile`'s.

    Raises
    ------
    ArchiveError
        When ``OUT.part`` holds towers of other inputs and ``discard_other`` is False: one
        line naming the file, the differences and the two ways on; the file is kept.
    """

    def __init__(
        self, path: str | os.PathLike, inputs: dict[str, Any], *, discard_other: bool = False
    ) -> None:
        super().__init__(path)
        self.inputs = inputs
        self.fingerprint = inputs_fingerprint(inputs)
        self.done: dict[int, Any] = {}
        self._committed = 0
        if self.part.exists() or self.part.is_symlink():
            self._open_existing(discard_other)
        if not self.resumed:
            self._create()

    # -------------------------------------------------------------- opening

    def _open_existing(self, discard_other: bool) -> None:
        shown = printable(os.fspath(self.part))
        foreign = ArchiveError(
            f"{shown} exists and is not a work file of rockscreen assess; refused: it is "
            "not replaced, move it away or choose another --out"
        )
        if not self.part.is_file() or self.part.is_symlink():
            raise foreign
        if self.part.stat().st_size and not is_hdf5(self.part):
            raise foreign
        verdict, reason = verify_assess_part(self.part)
        if verdict is None and reason == NOT_AN_ASSESS_PART:
            raise foreign
        if verdict is None:  # our own file, damaged (killed while created): start afresh
            self.discarded = reason
            self.part.unlink()
            return
        if verdict["fingerprint"] != self.fingerprint:
            stored = verdict["inputs"]
            differences = input_differences(stored, self.inputs) or ["the inputs' fingerprint"]
            if discard_other:
                self.discarded = "it holds towers of other inputs (" + "; ".join(differences) + ")"
                self.part.unlink()
                return
            raise ArchiveError(
                f"{shown} holds {verdict['committed']} tower(s) of an assess with other "
                f"inputs ({'; '.join(differences)}); refused, the file is kept: rerun with "
                "the same inputs to resume it, or pass --overwrite to discard it"
            )
        stored = _part_version(self.part)
        if stored != PART_VERSION:  # another layout of the towers' results: not resumable
            self.discarded = (
                f"it was written in another layout of the work file (part_version "
                f"{stored or 'none'}; this rockscreen writes {PART_VERSION})"
            )
            self.part.unlink()
            return
        try:
            with h5py.File(self.part, "r+") as f:
                n = verdict["committed"]
                for name in _COLUMNS:
                    f["towers"][name].resize((n,))  # rows after the last commit: dropped
                indices = f["towers/index"][:n]
                self.done = {}
                for start in range(0, n, READ_TOWERS):  # a part at a time, kept light
                    texts = f["towers/result"].asstr()[start : start + READ_TOWERS]
                    for i, text in zip(indices[start : start + READ_TOWERS], texts, strict=True):
                        light = light_result(decode_result(text))
                        light.pop("row", None)  # read back when written: rows()
                        self.done[int(i)] = light
        except (OSError, KeyError, ValueError, RuntimeError) as exc:
            self.discarded = f"it could not be reopened for writing ({str(exc)[:120]})"
            self.done = {}
            self.part.unlink(missing_ok=True)
            return
        self._committed = verdict["committed"]
        self.resumed = True

    def _create(self) -> None:
        try:
            with h5py.File(self.part, "w") as f:
                f.attrs["format"] = ASSESS_PART_FORMAT
                f.attrs["part_version"] = PART_VERSION
                f.attrs["fingerprint"] = self.fingerprint
                f.attrs["inputs"] = json.dumps(self.inputs, sort_keys=True)
                f.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(
                    timespec="seconds"
                )
                towers = f.create_group("towers")
                for name in _COLUMNS:
                    dtype = "i8" if name == "index" else _STR
                    towers.create_dataset(
                        name, shape=(0,), maxshape=(None,), dtype=dtype, chunks=(64,)
                    )
                f.attrs["committed"] = 0
                f.flush()
        except (OSError, RuntimeError) as exc:
            self.part.unlink(missing_ok=True)
            raise ArchiveError(
                f"{printable(os.fspath(self.part))}: the work file could not be created "
                f"({printable(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)})"
            ) from None
        self._committed = 0

    # -------------------------------------------------------------- writing

    @property
    def n_done(self) -> int:
        """Towers committed to the work file (resumed ones included)."""
        return self._committed

    def append(self, results: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
        """Keep finished towers: write, commit the count, flush; return them decoded.

        Parameters
        ----------
        results : iterable of dict
            Tower results, each with its inventory ``index`` and its ``row`` (with ``id``).

        Returns
        -------
        list of dict
            The results as a resumed run reads them back (:func:`decode_result`).

        Raises
        ------
        ArchiveError
            When the write fails (a full disk): one line naming the file and saying the
            towers committed before are kept.
        """
        if self._file is None:
            raise ArchiveError("the assess work file is not open (use it in a with block)")
        texts = [encode_result(item) for item in results]
        decoded = [decode_result(text) for text in texts]
        if not texts:
            return decoded
        n, k = self._committed, len(texts)
        try:
            towers = self._file["towers"]
            columns = {
                "index": np.asarray([item["index"] for item in decoded], dtype="i8"),
                "id": np.asarray([str(item["row"]["id"]) for item in decoded], dtype=object),
                "result": np.asarray(texts, dtype=object),
                "sha256": np.asarray(
                    [hashlib.sha256(t.encode("utf-8")).hexdigest() for t in texts], dtype=object
                ),
                "row": np.asarray([encode_result(item["row"]) for item in decoded], dtype=object),
            }
            for name, data in columns.items():
                towers[name].resize((n + k,))
                towers[name][n:] = data
            self._file.attrs["committed"] = n + k  # the commit: after the rows
            self._file.flush()
        except (OSError, RuntimeError) as exc:
            self._close()
            self.write_failed = True
            what = "the disk is full" if is_disk_full(exc) else f"writing failed ({exc})"
            raise ArchiveError(
                f"{printable(os.fspath(self.part))}: {printable(what.splitlines()[0])}; the "
                f"{n} tower(s) committed before are kept: free space and rerun to resume"
            ) from None
        self._committed = n + k
        return decoded

    def tables(self, indices: Sequence[int], table: str) -> Iterator[list[dict[str, Any]]]:
        """Yield the rows of one table of the given towers, read back a part at a time.

        Parameters
        ----------
        indices : sequence of int
            Towers (inventory index) in the work file, in the order wanted.
        table : {"stripes", "outcomes", "ida"}
            The table.

        Yields
        ------
        list of dict
            The rows of up to :data:`READ_TOWERS` towers, in the order of ``indices``.

        Raises
        ------
        ArchiveError
            For a tower not committed to the work file or whose text does not match its
            SHA-256 (the file changed since it was written): one line naming the file.
        """
        shown = printable(os.fspath(self.part))
        with reading(self.part, "work file"), h5py.File(self.part, "r") as f:
            towers = f["towers"]
            n = int(f.attrs["committed"])
            where = {int(i): row for row, i in enumerate(towers["index"][:n])}
            for start in range(0, len(indices), READ_TOWERS):
                wanted = list(indices[start : start + READ_TOWERS])
                if any(i not in where for i in wanted):
                    raise ArchiveError(f"{shown}: a tower is missing from the work file")
                rows = sorted({where[i] for i in wanted})
                texts = dict(zip(rows, towers["result"].asstr()[rows], strict=True))
                digests = dict(zip(rows, towers["sha256"].asstr()[rows], strict=True))
                part: list[dict[str, Any]] = []
                for i in wanted:
                    text = texts[where[i]]
                    if hashlib.sha256(text.encode("utf-8")).hexdigest() != digests[where[i]]:
                        raise ArchiveError(
                            f"{shown}: tower {i} changed since it was written (its SHA-256 "
                            "differs); the archive was not written: rerun the same command"
                        )
                    part.extend(decode_data(json.loads(text).get(table, [])))
                yield part

    def rows(self, indices: Sequence[int]) -> list[dict[str, Any]]:
        """Return the summary rows of the given towers (``/towers/row``), in that order.

        Parameters
        ----------
        indices : sequence of int
            Towers (inventory index) in the work file: a part (:data:`READ_TOWERS`).

        Returns
        -------
        list of dict
            Each tower's summary row as its result holds it.

        Raises
        ------
        ArchiveError
            For a tower not committed to the work file, or a row that is not its tower's
            (the file changed since it was written): one line naming the file.
        """
        shown = printable(os.fspath(self.part))
        with reading(self.part, "work file"), h5py.File(self.part, "r") as f:
            towers = f["towers"]
            n = int(f.attrs["committed"])
            where = {int(i): row for row, i in enumerate(towers["index"][:n])}
            if any(i not in where for i in indices):
                raise ArchiveError(f"{shown}: a tower is missing from the work file")
            at = sorted({where[i] for i in indices})
            texts = dict(zip(at, towers["row"].asstr()[at], strict=True))
            ids = dict(zip(at, towers["id"].asstr()[at], strict=True))
        out = []
        for i in indices:
            row = decode_result(texts[where[i]])
            if str(row.get("id")) != ids[where[i]]:
                raise ArchiveError(
                    f"{shown}: tower {i}'s summary row is not its own (the file changed "
                    "since it was written); the archive was not written: rerun the same command"
                )
            out.append(row)
        return out


def suite_digest(arrays: Iterable[tuple[str, float, Iterable[Any]]]) -> str:
    """Return the SHA-256 of a record suite's content.

    Parameters
    ----------
    arrays : iterable of (str, float, iterable of array or None)
        Per record: its name, its time step [s] and its components (None: absent).

    Returns
    -------
    str
        64 hexadecimal digits.
    """
    digest = hashlib.sha256()
    for name, dt, components in arrays:
        digest.update(json.dumps([name, None if math.isnan(dt) else dt]).encode("utf-8"))
        for array in components:
            if array is None:
                digest.update(b"none")
            else:
                digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    return digest.hexdigest()
