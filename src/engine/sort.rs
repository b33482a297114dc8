//! One stable sort for the whole crate, shared by every element type.
//! May import: nothing of the crate.
//!
//! `slice::sort_by` is generic over the element and the comparison: each call site with its
//! own closure gets its own copy of the standard library's sort, about 5 KB of WebAssembly each
//! (27 copies, 147 KB, when every call site had its own). [`sort_by`] sorts the positions
//! `0..n` instead, with one comparison type for all callers, so the sort itself is compiled
//! once; each element type adds only the small loop that moves its elements into that order.
//! The result is exactly `slice::sort_by`'s: a stable sort's result is the one order that keeps
//! equal elements as they came, whatever sorted it.

use std::cmp::Ordering;

/// Sorts `v` stably by `cmp`, as `v.sort_by(cmp)` would. Already-sorted input (the common
/// case: time-stamped records) costs one pass and no allocation.
pub fn sort_by<T>(v: &mut [T], mut cmp: impl FnMut(&T, &T) -> Ordering) {
    if v.windows(2).all(|w| cmp(&w[0], &w[1]) != Ordering::Greater) {
        return;
    }
    let order = stable_order(v.len(), &mut |a, b| cmp(&v[a], &v[b]));
    permute(v, &order);
}

/// Sorts `v` stably by the key `key`, as `v.sort_by_key(key)` would.
pub fn sort_by_key<T, K: Ord>(v: &mut [T], mut key: impl FnMut(&T) -> K) {
    sort_by(v, |a, b| key(a).cmp(&key(b)));
}

/// Sorts `v` stably in its natural order, as `v.sort()` would.
pub fn sort<T: Ord>(v: &mut [T]) {
    sort_by(v, T::cmp);
}

/// The positions `0..n` in the stable order of `cmp` (which compares the elements at two
/// positions): the one sort the crate compiles.
fn stable_order(n: usize, cmp: &mut dyn FnMut(usize, usize) -> Ordering) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| cmp(a, b));
    order
}

/// Rearranges `v` so that its element `k` is the one that was at `order[k]` (`order` a
/// permutation of `0..v.len()`), with swaps only: no copy or clone of an element.
fn permute<T>(v: &mut [T], order: &[usize]) {
    // `held[p]`: the original position of the element now at p; `at[i]`: where the element
    // originally at i is now.
    let mut held: Vec<usize> = (0..v.len()).collect();
    let mut at = held.clone();
    for (k, &want) in order.iter().enumerate() {
        let from = at[want];
        if from != k {
            v.swap(k, from);
            let displaced = held[k];
            held[from] = displaced;
            at[displaced] = from;
            held[k] = want;
            at[want] = k;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (no crate needed): xorshift64.
    fn numbers(seed: u64, n: usize, modulo: u64) -> Vec<u64> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                x % modulo
            })
            .collect()
    }

    #[test]
    fn same_order_as_the_standard_stable_sort() {
        for (seed, n, modulo) in [
            (1, 0, 5),
            (2, 1, 5),
            (3, 2, 2),
            (4, 50, 7),
            (5, 1000, 30),
            (6, 5000, 1_000_000),
        ] {
            // Pairs (key, original index): equal keys must keep their original order.
            let v: Vec<(u64, usize)> = numbers(seed, n, modulo).into_iter().zip(0..).collect();
            let mut ours = v.clone();
            let mut theirs = v.clone();
            sort_by(&mut ours, |a, b| a.0.cmp(&b.0));
            theirs.sort_by_key(|a| a.0);
            assert_eq!(ours, theirs, "seed {seed}, n {n}");
        }
    }

    #[test]
    fn floats_by_total_order_and_keys_and_strings() {
        let mut f = vec![3.5, -0.0, f64::NAN, 0.0, -2.0, f64::INFINITY, 1.0];
        let mut g = f.clone();
        sort_by(&mut f, f64::total_cmp);
        g.sort_by(f64::total_cmp);
        assert_eq!(
            f.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            g.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );

        let mut s: Vec<String> = ["b", "a", "c", "a2", ""]
            .iter()
            .map(|s| s.to_string())
            .collect();
        sort(&mut s);
        assert_eq!(s, ["", "a", "a2", "b", "c"]);

        let mut k = vec![(2, 'x'), (1, 'y'), (2, 'a'), (0, 'z')];
        sort_by_key(&mut k, |p| std::cmp::Reverse(p.0));
        assert_eq!(k, [(2, 'x'), (2, 'a'), (1, 'y'), (0, 'z')]);
    }

    #[test]
    fn sorted_input_is_left_alone() {
        let mut v: Vec<u32> = (0..100).collect();
        sort(&mut v);
        assert_eq!(v, (0..100).collect::<Vec<_>>());
    }
}
