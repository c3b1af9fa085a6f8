"""Slot storage for one kind of mesh element (vertex, edge, face or corner).

Each kind lives in a structure of numpy arrays indexed by *slot*. Users see
*ids*: integers handed out by a per-mesh counter and never reused. A slot freed by
a deletion is reused by the next creation, so memory follows the live element
count, not the history of edits.

Id -> slot lookup has a fast path: a bulk-built mesh (and every element appended
after it without reuse) keeps ``slot == id - base``. Only elements that land in a
reused slot are recorded in the ``moved`` dict, which never holds more entries
than there are live elements.

The scalar fields are exposed as ``memoryview`` objects (``views``), which read
and write single entries at close to list speed; the numpy arrays (``arrays``)
serve the vectorized bulk operations. Growing a table replaces both, so
operators call :meth:`Table.reserve` *before* they fetch views.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ._checks import shown
from .errors import InvalidArgumentError, UnknownIdError

# dtype and trailing shape of every field, per kind
FieldSpec = dict[str, tuple[Any, tuple[int, ...]]]


class Table:
    """The arrays, id counter and free slots of one element kind.

    Attributes:
        kind: "vertex", "edge", "face" or "corner", used in error messages.
        arrays: field name -> numpy array of shape ``(capacity, *tail)``.
        views: field name -> memoryview of the 1-D fields (scalar access).
        ids: ``(capacity,)`` int64 array, the id in each slot, -1 when free.
        idv: memoryview of ``ids``.
        n: slots ever used (the high-water mark); slots ``>= n`` are untouched.
        free: freed slots below ``n``, reused last-in first-out.
        base: ids of slots that were never reused are ``base + slot``.
        moved: id -> slot for ids that do not follow ``base + slot``.
        next_id: the id the next created element gets.
        floor: the first id this table handed out (:meth:`from_arrays` may start
            above 0); below it, an id was in an earlier mesh or never existed.
    """

    if TYPE_CHECKING:
        # scalar views of the fields appear as attributes of the same name
        # (``table.next``, see :meth:`_refresh_views`). Only the type checker
        # sees this: a real ``__getattr__`` would stop CPython from
        # specializing every attribute load on a table (3x slower each).
        def __getattr__(self, name: str) -> memoryview: ...

    def __init__(self, kind: str, spec: FieldSpec, capacity: int = 16) -> None:
        self.kind = kind
        self.spec = spec
        self.n = 0
        self.free: list[int] = []
        self.base = 0
        self.moved: dict[int, int] = {}
        self.next_id = 0
        self.floor = 0
        # live slots in id order, dropped on every create/delete
        self._sorted_cache: np.ndarray | None = None
        self.arrays: dict[str, np.ndarray] = {}
        self.views: dict[str, memoryview] = {}
        self.ids = np.full(capacity, -1, dtype=np.int64)
        self.idv = self.ids.data
        for name, (dtype, tail) in spec.items():
            self.arrays[name] = np.zeros((capacity, *tail), dtype=dtype)
        self._refresh_views()

    # -- capacity -------------------------------------------------------------

    @property
    def capacity(self) -> int:
        return self.cap

    def _refresh_views(self) -> None:
        self.cap = len(self.ids)
        self.idv = self.ids.data
        self.views = {
            name: arr.data for name, arr in self.arrays.items() if arr.ndim == 1
        }
        for name, view in self.views.items():
            setattr(self, name, view)

    def add_fields(self, spec: FieldSpec) -> None:
        """Give every slot the fields of ``spec`` too, zeros (fields a kind has only
        once they are used). Replaces the views, as growing does."""
        self.spec = self.spec | spec
        for name, (dtype, tail) in spec.items():
            self.arrays[name] = np.zeros((self.cap, *tail), dtype=dtype)
        self._refresh_views()

    def reserve(self, count: int) -> None:
        """Make sure ``count`` more elements can be created without growing.

        Growing replaces every array and view, so callers fetch ``views`` after
        this call, never before.
        """
        if self.n + count <= self.cap or len(self.free) + self.cap - self.n >= count:
            return
        new_cap = max(self.capacity * 2, self.n + count, 16)
        self._resize(new_cap)

    def _resize(self, new_cap: int) -> None:
        ids = np.full(new_cap, -1, dtype=np.int64)
        ids[: self.n] = self.ids[: self.n]
        self.ids = ids
        for name, arr in self.arrays.items():
            grown = np.zeros((new_cap, *arr.shape[1:]), dtype=arr.dtype)
            grown[: self.n] = arr[: self.n]
            self.arrays[name] = grown
        self._refresh_views()

    # -- create / delete ------------------------------------------------------

    def alloc(self) -> int:
        """Create one element and return its slot (capacity must be reserved)."""
        eid = self.next_id
        self.next_id = eid + 1
        free = self.free
        if free:
            slot = free.pop()
            # recorded even when the slot is home to eid (adopted ids can leave
            # next_id short of base + n): a redundant entry costs less than the test
            self.moved[eid] = slot
        else:
            slot = self.n
            self.n = slot + 1
            if slot != eid - self.base:
                self.moved[eid] = slot
        self.idv[slot] = eid
        self._sorted_cache = None
        return slot

    def alloc_pair(self) -> tuple[int, int]:
        """Create two elements and return their slots (capacity must be reserved)."""
        free = self.free
        if len(free) < 2:
            return self.alloc(), self.alloc()
        # both slots reused: recorded as in alloc
        first, second = free.pop(), free.pop()
        eid = self.next_id
        self.next_id = eid + 2
        moved, idv = self.moved, self.idv
        moved[eid] = first
        moved[eid + 1] = second
        idv[first] = eid
        idv[second] = eid + 1
        self._sorted_cache = None
        return first, second

    def release(self, slot: int) -> None:
        """Delete the element in ``slot``; its id is never handed out again."""
        idv = self.idv
        eid = idv[slot]
        idv[slot] = -1
        if self.moved:
            self.moved.pop(eid, None)
        self.free.append(slot)
        self._sorted_cache = None

    # -- lookup ---------------------------------------------------------------

    def slot(self, eid: Any) -> int:
        """Return the slot of the live element ``eid``.

        Raises:
            InvalidArgumentError: ``eid`` is not an integer.
            UnknownIdError: ``eid`` names no live element.
        """
        if type(eid) is not int:
            eid = self._as_int(eid)
        s = eid - self.base
        if 0 <= s < self.n and self.idv[s] == eid:
            return s
        found = self.moved.get(eid)
        if found is None:
            raise UnknownIdError(self._missing_message(eid))
        return found

    def slots(self, eids: Any) -> np.ndarray | list[int]:
        """The slots of the live elements ``eids``, in their order.

        An int array is looked up in one vectorized pass (``(k,)`` int64 slots);
        any other iterable id by id (a list), which is faster for a few ids.

        Raises:
            InvalidArgumentError: an entry is not an integer.
            UnknownIdError: an entry names no live element (the first such, in
                order).
        """
        if not (isinstance(eids, np.ndarray) and eids.dtype.kind in "iu"):
            slot = self.slot
            return [slot(eid) for eid in eids]
        if _past_int64(eids):
            return [self.slot(int(eid)) for eid in eids.reshape(-1)]
        ids = eids.astype(np.int64).reshape(-1)
        slots = ids - self.base
        home = (slots >= 0) & (slots < self.n)
        home[home] = self.ids[slots[home]] == ids[home]
        for k in np.flatnonzero(~home).tolist():  # moved ids, or the first missing one
            slots[k] = self.slot(int(ids[k]))
        return slots

    def _as_int(self, eid: Any) -> int:
        if isinstance(eid, (bool, np.bool_)) or not hasattr(eid, "__index__"):
            article = "an" if self.kind[0] in "aeiou" else "a"
            raise InvalidArgumentError(
                f"expected {article} {self.kind} id (an integer), got {shown(eid)}")
        return int(eid.__index__())

    def _missing_message(self, eid: int) -> str:
        """Why ``eid`` (not live) names nothing: deleted when this table handed
        it out; below ``floor`` the table cannot tell whether the mesh it
        rebuilt had it (a bulk rebuild continues the old ids) or it never existed."""
        if self.floor <= eid < self.next_id:
            return f"{self.kind} {eid} was deleted"
        if 0 <= eid < self.floor:
            return (f"{self.kind} {eid} was deleted or never existed (this mesh was built "
                    f"with {self.kind} ids from {self.floor})")
        return f"{self.kind} {shown(eid)} does not exist"

    def is_live(self, eid: Any) -> bool:
        """True when ``eid`` names a live element of this kind (False for non-integers)."""
        if type(eid) is not int:
            if isinstance(eid, (bool, np.bool_)) or not hasattr(eid, "__index__"):
                return False
            eid = int(eid.__index__())
        s = eid - self.base
        if 0 <= s < self.n and self.idv[s] == eid:
            return True
        return eid in self.moved

    # -- bulk views -----------------------------------------------------------

    @property
    def count(self) -> int:
        """Number of live elements."""
        return self.n - len(self.free)

    def live_slots(self) -> np.ndarray:
        """``(count,)`` int64 slots of the live elements, in increasing id order."""
        cached = self._sorted_cache
        if cached is not None:
            return cached
        ids = self.ids[: self.n]
        slots = np.flatnonzero(ids >= 0)
        if self.moved:
            slots = slots[np.argsort(ids[slots], kind="stable")]
        self._sorted_cache = slots
        return slots

    def live_ids(self) -> np.ndarray:
        """``(count,)`` int64 ids of the live elements, increasing."""
        return self.ids[self.live_slots()]

    def copy(self) -> Table:
        """A deep copy sized to the used slots."""
        other = type(self).__new__(type(self))
        other.kind = self.kind
        other.spec = self.spec
        cap = max(self.n, 16)
        other.ids = np.full(cap, -1, dtype=np.int64)
        other.ids[: self.n] = self.ids[: self.n]
        other.arrays = {}
        for name, arr in self.arrays.items():
            dup = np.zeros((cap, *arr.shape[1:]), dtype=arr.dtype)
            dup[: self.n] = arr[: self.n]
            other.arrays[name] = dup
        other.n = self.n
        other.free = list(self.free)
        other.base = self.base
        other.moved = dict(self.moved)
        other.next_id = self.next_id
        other.floor = self.floor
        other._sorted_cache = None
        other._refresh_views()
        return other

    @classmethod
    def from_arrays(
        cls, kind: str, spec: FieldSpec, first_id: int, arrays: dict[str, np.ndarray],
        ids: np.ndarray | None = None,
    ) -> Table:
        """A table whose slots ``0..n-1`` hold ids ``first_id..first_id+n-1``, or
        the ``(n,)`` distinct ``ids`` given (then the next id handed out is past
        both ``first_id - 1`` and the largest of them).

        ``arrays`` gives every field of ``spec`` with ``n`` rows; they are
        adopted (not copied) when their dtype already matches.
        """
        table = cls.__new__(cls)
        table.kind = kind
        table.spec = spec
        count = len(next(iter(arrays.values()))) if arrays else 0
        table.n = count
        table.free = []
        table.base = first_id
        table.moved = {}
        table.next_id = first_id + count
        table.floor = first_id
        table._sorted_cache = None
        table.ids = np.arange(first_id, first_id + count, dtype=np.int64)
        table.arrays = {
            name: np.ascontiguousarray(arrays[name], dtype=dtype)
            for name, (dtype, _tail) in spec.items()
        }
        if ids is not None and count:
            table._adopt_ids(np.asarray(ids, dtype=np.int64))
        if count == 0:
            table._resize(16)
        table._refresh_views()
        return table

    def _adopt_ids(self, ids: np.ndarray) -> None:
        """Give the ``n`` slots ``ids``: those that do not follow ``base + slot``
        (base: the first one's) go to ``moved``."""
        self.ids = ids
        self.base = int(ids[0])
        off = np.flatnonzero(ids != self.base + np.arange(len(ids)))
        self.moved = dict(zip(ids[off].tolist(), off.tolist(), strict=True))
        self.next_id = max(self.next_id - len(ids), int(ids.max()) + 1)
        self.floor = min(self.floor, int(ids.min()))


def _past_int64(ids: np.ndarray) -> bool:
    """True when the unsigned ``ids`` hold one past int64's range, which a cast
    would wrap to a negative id (the error would name another id)."""
    return ids.dtype.kind == "u" and ids.size > 0 and int(ids.max()) > np.iinfo(np.int64).max
