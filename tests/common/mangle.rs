//! Mangling JSON documents for the reader property tests.

use serde_json::Value;

/// Replaces the node reached by following `path` (indices taken modulo the container sizes;
/// a path that ends early at a leaf replaces that leaf).
pub(crate) fn replace_at(v: &mut Value, path: &[usize], new: Value) {
    let Some((&k, rest)) = path.split_first() else {
        *v = new;
        return;
    };
    match v {
        Value::Array(a) if !a.is_empty() => {
            let n = a.len();
            replace_at(&mut a[k % n], rest, new);
        }
        Value::Object(m) if !m.is_empty() => {
            let n = m.len();
            if let Some((_, x)) = m.iter_mut().nth(k % n) {
                replace_at(x, rest, new);
            }
        }
        _ => *v = new,
    }
}
