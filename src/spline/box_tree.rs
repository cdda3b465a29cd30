//! A bounding-box hierarchy over pieces of a curve or patches of a surface, for searches that
//! prune by distance (the closest point): a balanced binary tree whose nodes hold items near
//! each other in space, the box of them all, and the smallest key (parameter) among them.

use super::vector::Point;

/// One item to index: the bounding box of its control points and its key (the smallest
/// parameter it covers: a number for a curve piece, `(u, v)` for a surface patch, compared
/// lexicographically).
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoxItem<K> {
    pub(crate) min: Point,
    pub(crate) max: Point,
    pub(crate) key: K,
}

/// A node of the hierarchy: the bounding box of some items, the smallest key among them,
/// and either its two halves or (a leaf) its one item.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoxNode<K> {
    pub(crate) min: Point,
    pub(crate) max: Point,
    pub(crate) from: K,
    pub(crate) content: NodeContent,
}

/// What a node holds: indices of its halves' nodes, or of its one item.
#[derive(Debug, Clone, Copy)]
pub(crate) enum NodeContent {
    Halves(usize, usize),
    Item(usize),
}

impl<K> BoxNode<K> {
    /// The squared distance from `q` to the box (in its first `coordinates`): a lower bound
    /// for its items.
    #[inline]
    pub(crate) fn squared_distance(&self, q: Point, coordinates: usize) -> f64 {
        box_squared_distance(&self.min, &self.max, q, coordinates)
    }
}

/// The hierarchy over `items`: `nodes[0]` is the root (no nodes when there are no items).
/// Items are halved by count at the median of their boxes' centres along the longest side of
/// the node's box, so that each node holds items near each other in space (a long curve that
/// doubles back has consecutive pieces far apart, and boxes of consecutive pieces would cover
/// it all), and the depth stays `⌈log2(items)⌉`.
pub(crate) fn build<K: Copy + PartialOrd>(items: &[BoxItem<K>]) -> Vec<BoxNode<K>> {
    let mut nodes = Vec::with_capacity(2 * items.len());
    if !items.is_empty() {
        let mut order: Vec<usize> = (0..items.len()).collect();
        build_node(items, &mut order, &mut nodes);
    }
    nodes
}

/// Appends the subtree over the items `order` (indices, non-empty) to `nodes`; returns its
/// index.
fn build_node<K: Copy + PartialOrd>(
    items: &[BoxItem<K>],
    order: &mut [usize],
    nodes: &mut Vec<BoxNode<K>>,
) -> usize {
    let index = nodes.len();
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    let mut from = items[order[0]].key;
    for item in order.iter().map(|&i| &items[i]) {
        for c in 0..3 {
            min[c] = min[c].min(item.min[c]);
            max[c] = max[c].max(item.max[c]);
        }
        if item.key < from {
            from = item.key;
        }
    }
    nodes.push(BoxNode {
        min,
        max,
        from,
        content: NodeContent::Item(order[0]),
    });
    if order.len() > 1 {
        let axis = (0..3)
            .max_by(|&a, &b| (max[a] - min[a]).total_cmp(&(max[b] - min[b])))
            .unwrap_or(0);
        let centre = |i: usize| items[i].min[axis] + items[i].max[axis];
        let middle = order.len() / 2;
        order.select_nth_unstable_by(middle, |&a, &b| centre(a).total_cmp(&centre(b)));
        let (left, right) = order.split_at_mut(middle);
        let left = build_node(items, left, nodes);
        let right = build_node(items, right, nodes);
        nodes[index].content = NodeContent::Halves(left, right);
    }
    index
}

/// The squared distance from `q` to the box `[min, max]` (in its first `coordinates`).
#[inline]
pub(crate) fn box_squared_distance(min: &Point, max: &Point, q: Point, coordinates: usize) -> f64 {
    let mut sum = 0.0;
    for ((&low, &high), &value) in min.iter().zip(max).zip(&q).take(coordinates) {
        let below = low - value;
        let above = value - high;
        let gap = if below > 0.0 {
            below
        } else if above > 0.0 {
            above
        } else {
            0.0
        };
        sum += gap * gap;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_is_one_leaf_and_nodes_hold_their_items() {
        let items: Vec<BoxItem<(f64, f64)>> = (0..7)
            .map(|k| {
                let x = f64::from(k);
                BoxItem {
                    min: [x, 0.0, 0.0],
                    max: [x + 0.5, 1.0, 0.0],
                    key: (x, -x),
                }
            })
            .collect();
        let nodes = build(&items);
        assert_eq!(nodes.len(), 2 * items.len() - 1);
        let mut leaves: Vec<usize> = nodes
            .iter()
            .filter_map(|n| match n.content {
                NodeContent::Item(i) => Some(i),
                NodeContent::Halves(..) => None,
            })
            .collect();
        leaves.sort_unstable();
        assert_eq!(leaves, (0..7).collect::<Vec<_>>());
        assert_eq!(nodes[0].from, (0.0, -0.0));
        assert_eq!(nodes[0].min, [0.0, 0.0, 0.0]);
        assert_eq!(nodes[0].max, [6.5, 1.0, 0.0]);
        assert_eq!(nodes[0].squared_distance([10.0, 0.5, 0.0], 3), 3.5 * 3.5);
        assert_eq!(box_squared_distance(&[0.0; 3], &[1.0; 3], [0.5; 3], 3), 0.0);
    }
}
