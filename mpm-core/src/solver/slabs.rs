//! Particle-to-grid sums in parallel without locks: points are bucketed into slabs of node
//! rows along the last axis by their lowest node; slabs of one colour (even or odd) touch
//! disjoint node ranges (a slab is at least support − 1 rows wide, so a point reaches at
//! most into the next slab), and each slab adds its points in index order, so the sums do
//! not depend on the number of threads. The run's transfer (`scatter`) and the derivative
//! pass's (`tangent`) share it.

/// Points bucketed into slabs of `width` node rows along the last axis.
#[derive(Clone, Default)]
pub(super) struct Slabs {
    width: usize,
    count: usize,
    /// Node rows a point reaches, at most (its lowest row and the next support − 1).
    support: usize,
    /// The points, slab after slab, each slab's in index order.
    order: Vec<u32>,
    /// Where each slab's points start in `order` (and the end).
    start: Vec<usize>,
}

impl Slabs {
    /// Stable counting sort of `points` points by the slab of their lowest node row
    /// (`lowest_row`), on a grid of `node_rows` node rows along its last axis, each point
    /// reaching at most `support` rows.
    pub(super) fn bucket(
        &mut self,
        points: usize,
        (node_rows, support): (usize, usize),
        lowest_row: impl Fn(usize) -> usize,
    ) {
        // about 32 slabs over the rows a full-support point's lowest node can be in; the
        // slabs cover every row, since a point of smaller reach can start higher
        let rows = (node_rows + 1).saturating_sub(support).max(1);
        self.width = rows.div_ceil(32).max(support - 1).max(1);
        self.count = node_rows.max(1).div_ceil(self.width);
        self.support = support;
        let slab_of = |i: usize| lowest_row(i) / self.width;
        self.start.clear();
        self.start.resize(self.count + 1, 0);
        for i in 0..points {
            self.start[slab_of(i) + 1] += 1;
        }
        for k in 0..self.count {
            self.start[k + 1] += self.start[k];
        }
        self.order.resize(points, 0);
        let mut next = self.start.clone();
        for i in 0..points {
            let k = slab_of(i);
            self.order[next[k]] = i as u32;
            next[k] += 1;
        }
    }

    /// The slabs of `colour` (0 or 1) with the first node each reaches and the nodes it
    /// reaches: slab k, node rows k w .. (k + 1) w + support − 2 of `nodes`, `stride`
    /// nodes a row.
    pub(super) fn parts<'a, N>(
        &self,
        nodes: &'a mut [N],
        colour: usize,
        stride: usize,
    ) -> Vec<(usize, usize, &'a mut [N])> {
        let mut parts = Vec::new();
        let mut rest: &mut [N] = nodes;
        let mut consumed = 0;
        for k in (colour..self.count).step_by(2) {
            let start = k * self.width * stride;
            let end =
                (((k + 1) * self.width + self.support - 1) * stride).min(consumed + rest.len());
            let tail = std::mem::take(&mut rest);
            let (_, tail) = tail.split_at_mut(start - consumed);
            let (mine, tail) = tail.split_at_mut(end - start);
            rest = tail;
            consumed = end;
            parts.push((k, start, mine));
        }
        parts
    }

    /// The points of slab `k`, in index order.
    pub(super) fn points(&self, k: usize) -> &[u32] {
        &self.order[self.start[k]..self.start[k + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::Slabs;

    /// A point of small reach whose lowest node is the grid's top row lands in a slab, and
    /// the slabs of one colour get disjoint node ranges that hold each of their points' rows.
    #[test]
    fn every_lowest_row_has_a_slab_and_its_rows() {
        let (node_rows, support, stride) = (40, 4, 3);
        let lowest = [0, 5, 17, 36, 39, 38, 12];
        let mut slabs = Slabs::default();
        slabs.bucket(lowest.len(), (node_rows, support), |i| lowest[i]);
        let mut nodes = vec![0u8; node_rows * stride];
        let mut seen = Vec::new();
        for colour in 0..2 {
            for (k, start, mine) in slabs.parts(&mut nodes, colour, stride) {
                for &i in slabs.points(k) {
                    let i = i as usize;
                    let reach = (support.min(node_rows - lowest[i])) * stride;
                    assert!(lowest[i] * stride >= start);
                    assert!(lowest[i] * stride + reach <= start + mine.len());
                    seen.push(i);
                }
            }
        }
        seen.sort();
        assert_eq!(seen, (0..lowest.len()).collect::<Vec<_>>());
    }
}
