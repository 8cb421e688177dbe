//! The status of a line sweep: the items (edges) the sweep line crosses,
//! in their order along it.
//!
//! An item's place is found once, when it is inserted, by a comparison the
//! caller gives against the items already there; afterwards the item is
//! named by its index, so that removing it and finding its neighbours take
//! no comparison at all. A comparison that is not a consistent order (as
//! floating point can make it near a crossing) then only puts an item in a
//! wrong place: nothing can panic or loop, as a `BTreeMap` with such an
//! order might.
//!
//! A treap: a binary search tree in item order, a heap in fixed
//! pseudo-random priorities, so that its depth is O(log n) expected
//! whatever the order of insertions; every operation is O(log n) expected.

const NIL: u32 = u32::MAX;

#[derive(Clone, Copy)]
struct Node {
    left: u32,
    right: u32,
    parent: u32,
    priority: u64,
    present: bool,
}

/// Items `0..capacity`, each in the status at most once.
pub(super) struct SweepStatus {
    nodes: Vec<Node>,
    root: u32,
}

impl SweepStatus {
    pub(super) fn new(capacity: usize) -> Self {
        let nodes = (0..capacity as u64)
            .map(|i| Node {
                left: NIL,
                right: NIL,
                parent: NIL,
                priority: mix(i),
                present: false,
            })
            .collect();
        SweepStatus { nodes, root: NIL }
    }

    /// Inserts `item` (not in the status) after every item for which
    /// `after` is true, walking down from the root.
    pub(super) fn insert(&mut self, item: usize, mut after: impl FnMut(usize) -> bool) {
        let x = item as u32;
        let mut parent = NIL;
        let mut go_right = false;
        let mut at = self.root;
        while at != NIL {
            parent = at;
            go_right = after(at as usize);
            at = if go_right {
                self.nodes[at as usize].right
            } else {
                self.nodes[at as usize].left
            };
        }
        let node = &mut self.nodes[item];
        *node = Node {
            left: NIL,
            right: NIL,
            parent,
            priority: node.priority,
            present: true,
        };
        if parent == NIL {
            self.root = x;
        } else if go_right {
            self.nodes[parent as usize].right = x;
        } else {
            self.nodes[parent as usize].left = x;
        }
        while self.nodes[item].parent != NIL
            && self.nodes[self.nodes[item].parent as usize].priority < self.nodes[item].priority
        {
            self.rotate_up(x);
        }
    }

    /// Removes `item`, if it is in the status.
    pub(super) fn remove(&mut self, item: usize) {
        if !self.nodes[item].present {
            return;
        }
        let x = item as u32;
        // Rotate it down to a leaf, its higher-priority child up.
        loop {
            let Node { left, right, .. } = self.nodes[item];
            let child = match (left, right) {
                (NIL, NIL) => break,
                (l, NIL) => l,
                (NIL, r) => r,
                (l, r) => {
                    if self.nodes[l as usize].priority > self.nodes[r as usize].priority {
                        l
                    } else {
                        r
                    }
                }
            };
            self.rotate_up(child);
        }
        let parent = self.nodes[item].parent;
        if parent == NIL {
            self.root = NIL;
        } else if self.nodes[parent as usize].left == x {
            self.nodes[parent as usize].left = NIL;
        } else {
            self.nodes[parent as usize].right = NIL;
        }
        let node = &mut self.nodes[item];
        node.parent = NIL;
        node.present = false;
    }

    /// The item just before `item` (which is in the status).
    pub(super) fn prev(&self, item: usize) -> Option<usize> {
        self.step(item as u32, |n| n.left, |n| n.right)
    }

    /// The item just after `item` (which is in the status).
    pub(super) fn next(&self, item: usize) -> Option<usize> {
        self.step(item as u32, |n| n.right, |n| n.left)
    }

    /// The last item for which `after` is true and the first for which it
    /// is false: where an item with that comparison would go.
    pub(super) fn locate(
        &self,
        mut after: impl FnMut(usize) -> bool,
    ) -> (Option<usize>, Option<usize>) {
        let (mut before, mut behind) = (None, None);
        let mut at = self.root;
        while at != NIL {
            if after(at as usize) {
                before = Some(at as usize);
                at = self.nodes[at as usize].right;
            } else {
                behind = Some(at as usize);
                at = self.nodes[at as usize].left;
            }
        }
        (before, behind)
    }

    /// In-order neighbour: down `first` then as far as possible along
    /// `then`, or up to the first ancestor reached from its `then` side.
    fn step(
        &self,
        x: u32,
        first: impl Fn(&Node) -> u32,
        then: impl Fn(&Node) -> u32,
    ) -> Option<usize> {
        let mut at = first(&self.nodes[x as usize]);
        if at != NIL {
            while then(&self.nodes[at as usize]) != NIL {
                at = then(&self.nodes[at as usize]);
            }
            return Some(at as usize);
        }
        let mut child = x;
        let mut up = self.nodes[x as usize].parent;
        while up != NIL && first(&self.nodes[up as usize]) == child {
            child = up;
            up = self.nodes[up as usize].parent;
        }
        (up != NIL).then_some(up as usize)
    }

    /// Rotates `x` above its parent, keeping the in-order sequence.
    fn rotate_up(&mut self, x: u32) {
        let p = self.nodes[x as usize].parent;
        let g = self.nodes[p as usize].parent;
        if self.nodes[p as usize].left == x {
            let b = self.nodes[x as usize].right;
            self.nodes[p as usize].left = b;
            if b != NIL {
                self.nodes[b as usize].parent = p;
            }
            self.nodes[x as usize].right = p;
        } else {
            let b = self.nodes[x as usize].left;
            self.nodes[p as usize].right = b;
            if b != NIL {
                self.nodes[b as usize].parent = p;
            }
            self.nodes[x as usize].left = p;
        }
        self.nodes[p as usize].parent = x;
        self.nodes[x as usize].parent = g;
        if g == NIL {
            self.root = x;
        } else if self.nodes[g as usize].left == p {
            self.nodes[g as usize].left = x;
        } else {
            self.nodes[g as usize].right = x;
        }
    }
}

/// SplitMix64's output function: fixed, well-spread priorities.
fn mix(i: u64) -> u64 {
    let mut z = i.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The items in order.
    fn items(s: &SweepStatus) -> Vec<usize> {
        let mut first = s.root;
        if first == NIL {
            return Vec::new();
        }
        while s.nodes[first as usize].left != NIL {
            first = s.nodes[first as usize].left;
        }
        std::iter::successors(Some(first as usize), |&i| s.next(i)).collect()
    }

    proptest! {
        /// Against a sorted vector: items inserted by key and removed in any
        /// order keep their order; neighbours and locate agree.
        #[test]
        fn the_status_is_a_sorted_list(
            keys in prop::collection::vec(0..50i32, 1..60),
            removals in prop::collection::vec(any::<prop::sample::Index>(), 0..80),
        ) {
            let mut status = SweepStatus::new(keys.len());
            let mut model: Vec<usize> = Vec::new();
            let key = |i: usize| (keys[i], i);
            for i in 0..keys.len() {
                status.insert(i, |t| key(t) < key(i));
                let at = model.partition_point(|&t| key(t) < key(i));
                model.insert(at, i);
                if let Some(removal) = removals.get(i).filter(|_| i % 3 == 2) {
                    let gone = model.remove(removal.index(model.len()));
                    status.remove(gone);
                }
                prop_assert_eq!(items(&status), model.clone());
                for (k, &m) in model.iter().enumerate() {
                    prop_assert_eq!(status.prev(m), k.checked_sub(1).map(|j| model[j]));
                    prop_assert_eq!(status.next(m), model.get(k + 1).copied());
                }
                let probe = (25, usize::MAX / 2);
                let split = model.partition_point(|&t| key(t) < probe);
                prop_assert_eq!(
                    status.locate(|t| key(t) < probe),
                    (split.checked_sub(1).map(|j| model[j]), model.get(split).copied())
                );
            }
        }
    }

    #[test]
    fn a_thousand_sorted_insertions_stay_shallow() {
        let n = 1000;
        let mut status = SweepStatus::new(n);
        for i in 0..n {
            status.insert(i, |t| t < i);
        }
        let depth = |mut x: u32| {
            let mut d = 0;
            while x != NIL {
                x = status.nodes[x as usize].parent;
                d += 1;
            }
            d
        };
        let deepest = (0..n as u32).map(depth).max().unwrap_or(0);
        assert!(deepest < 40, "depth {deepest}");
        assert_eq!(items(&status), (0..n).collect::<Vec<_>>());
    }
}
