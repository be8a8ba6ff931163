//! Chaining segments into polylines: segments given as pairs of point ids are joined end to end
//! wherever exactly two of them meet at a point. Used for intersection curves (thesis §2.2) and for
//! the lines of drawings, so that both come out as polylines rather than a soup of segments.

/// One chain of points; `closed` when its last point is its first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Chain {
    /// Point ids in order; a closed chain repeats its first id at the end.
    pub points: Vec<u32>,
    /// The chain is a loop.
    pub closed: bool,
}

/// Chains `segments` (pairs of ids below `point_count`, each at most once, no point to itself):
/// first the open chains, from each point where other than two segments meet (in id order), then
/// the loops (from their lowest-numbered segment). The result depends only on the input's order.
pub(crate) fn chain(point_count: usize, segments: &[[u32; 2]]) -> Vec<Chain> {
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); point_count];
    for (s, &[a, b]) in segments.iter().enumerate() {
        incident[a as usize].push(s as u32);
        incident[b as usize].push(s as u32);
    }
    let mut walker = Walker {
        segments,
        incident: &incident,
        used: vec![false; segments.len()],
    };
    let mut chains = Vec::new();
    for (point, around) in incident.iter().enumerate() {
        if around.len() != 2 {
            for &s in around {
                if !walker.used[s as usize] {
                    chains.push(walker.walk(point as u32, s));
                }
            }
        }
    }
    for (s, segment) in segments.iter().enumerate() {
        if !walker.used[s] {
            chains.push(walker.walk(segment[0], s as u32));
        }
    }
    chains
}

struct Walker<'a> {
    segments: &'a [[u32; 2]],
    incident: &'a [Vec<u32>],
    used: Vec<bool>,
}

impl Walker<'_> {
    /// Follows segments from `from` along `first` while each point passes exactly two on.
    fn walk(&mut self, from: u32, first: u32) -> Chain {
        let mut points = vec![from];
        let (mut at, mut segment) = (from, first);
        loop {
            self.used[segment as usize] = true;
            let [a, b] = self.segments[segment as usize];
            at = if a == at { b } else { a };
            points.push(at);
            let around = &self.incident[at as usize];
            if around.len() != 2 {
                return Chain {
                    points,
                    closed: false,
                };
            }
            match around.iter().find(|&&s| !self.used[s as usize]) {
                Some(&s) => segment = s,
                None => {
                    let closed = at == from;
                    return Chain { points, closed };
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_chains_start_at_ends_and_junctions_then_loops() {
        // 0-1-2 open; 3-4-5-3 a loop; 6 a junction of three segments to 7, 8, 9.
        let segments = [
            [1, 2],
            [3, 4],
            [0, 1],
            [4, 5],
            [5, 3],
            [6, 7],
            [8, 6],
            [6, 9],
        ];
        let chains = chain(10, &segments);
        let points: Vec<&[u32]> = chains.iter().map(|c| c.points.as_slice()).collect();
        assert_eq!(
            points,
            [&[0, 1, 2][..], &[6, 7], &[6, 8], &[6, 9], &[3, 4, 5, 3]]
        );
        assert_eq!(
            chains.iter().map(|c| c.closed).collect::<Vec<_>>(),
            [false, false, false, false, true]
        );
    }
}
