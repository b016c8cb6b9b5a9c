//! How the levels spread their work: over all cores (rayon) with the
//! `parallel` feature, one item after the other in the calling thread
//! without it (the browser's wasm, which has no threads). Either way the
//! results come back in the items' order, so a choice depends only on the
//! position and the bot's seed, never on how the work was spread.

/// `f` of every item of `items` with its index, in the items' order.
pub fn map<T, R, F>(items: &[T], f: F) -> Vec<R>
where
    T: Sync,
    R: Send,
    F: Fn(usize, &T) -> R + Sync + Send,
{
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items
            .par_iter()
            .enumerate()
            .map(|(i, item)| f(i, item))
            .collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        items
            .iter()
            .enumerate()
            .map(|(i, item)| f(i, item))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_back_in_the_items_order_with_their_indices() {
        let items: Vec<u64> = (0..1000).map(|k| k * 7 % 101).collect();
        let out = map(&items, |i, &x| (i, x * x));
        assert_eq!(out.len(), items.len());
        for (k, (i, sq)) in out.into_iter().enumerate() {
            assert_eq!((i, sq), (k, items[k] * items[k]));
        }
    }
}
