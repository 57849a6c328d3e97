//! Ordering bodies parents first, and finding the cycles that make it
//! impossible: the one place both the resolver (with spans) and the API
//! ([`System::add_bodies`](super::System::add_bodies)) order bodies.

/// Bodies in an order where each comes after its parent, and the parent
/// cycles that keep the others out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParentOrder {
    /// Indices, parents first.
    pub order: Vec<usize>,
    /// Each cycle once, as indices in the order of following parents.
    pub cycles: Vec<Vec<usize>>,
}

/// Orders items given the index of each one's parent among them (`None`:
/// the parent is outside the set, such as `N` or a body already added).
pub fn order_parents_first(parents: &[Option<usize>]) -> ParentOrder {
    let n = parents.len();
    let mut placed = vec![false; n];
    let mut order = Vec::with_capacity(n);
    loop {
        let mut progress = false;
        for i in 0..n {
            if !placed[i] && parents[i].is_none_or(|j| placed[j]) {
                placed[i] = true;
                order.push(i);
                progress = true;
            }
        }
        if !progress {
            break;
        }
    }
    // What is left is on a cycle or below one: follow parents from each
    // until an item repeats; report each cycle once.
    let mut reported = vec![false; n];
    let mut cycles = Vec::new();
    for start in 0..n {
        if placed[start] || reported[start] {
            continue;
        }
        let mut path: Vec<usize> = Vec::new();
        let mut cur = Some(start);
        while let Some(i) = cur {
            if let Some(pos) = path.iter().position(|p| *p == i) {
                let cycle = path[pos..].to_vec();
                if !cycle.iter().any(|k| reported[*k]) {
                    cycles.push(cycle);
                }
                break;
            }
            path.push(i);
            cur = parents[i];
        }
        for k in path {
            reported[k] = true;
        }
    }
    ParentOrder { order, cycles }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parents_come_first_and_each_cycle_is_reported_once() {
        // 0 <- 2 <- 1; 3 <-> 4 with 5 below the cycle.
        let p = [None, Some(2), Some(0), Some(4), Some(3), Some(3)];
        let o = order_parents_first(&p);
        assert_eq!(o.order, vec![0, 2, 1]);
        assert_eq!(o.cycles, vec![vec![3, 4]]);
        let own = order_parents_first(&[Some(0)]);
        assert_eq!(own.cycles, vec![vec![0]]);
    }
}
