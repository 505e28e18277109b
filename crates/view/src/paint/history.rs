//! Undo and redo of paint: each stroke (and each clear) keeps the paint layer as it was before,
//! so undo gives back exactly the earlier layer, bit for bit.

use cuticle_groom::Absorption;

/// The paint of every strand.
pub type PaintLayer = Vec<Option<Absorption>>;

/// Layers before (undo) and after (redo) the current one.
#[derive(Clone, Debug, Default)]
pub struct History {
    undo: Vec<PaintLayer>,
    redo: Vec<PaintLayer>,
}

/// Steps kept; the oldest go first.
const LIMIT: usize = 200;

impl History {
    /// Records `before`, the layer as it was before an edit; the redo steps are dropped.
    pub fn record(&mut self, before: PaintLayer) {
        self.undo.push(before);
        if self.undo.len() > LIMIT {
            self.undo.remove(0);
        }
        self.redo.clear();
    }

    /// The layer before `current`, if any; `current` becomes redoable.
    pub fn undo(&mut self, current: &PaintLayer) -> Option<PaintLayer> {
        let before = self.undo.pop()?;
        self.redo.push(current.clone());
        Some(before)
    }

    /// The layer undone last, if any; `current` becomes undoable.
    pub fn redo(&mut self, current: &PaintLayer) -> Option<PaintLayer> {
        let after = self.redo.pop()?;
        self.undo.push(current.clone());
        Some(after)
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Forgets every step (a new groom has other strands).
    pub fn clear(&mut self) {
        self.undo.clear();
        self.redo.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undo_and_redo_walk_the_layers() {
        let a: PaintLayer = vec![None, None];
        let b: PaintLayer = vec![Some(Absorption::MuA([1.0, 2.0, 3.0])), None];
        let c: PaintLayer = vec![None, Some(Absorption::MuA([0.5, 0.5, 0.5]))];
        let mut h = History::default();
        h.record(a.clone());
        h.record(b.clone());
        assert_eq!(h.undo(&c), Some(b.clone()));
        assert_eq!(h.undo(&b), Some(a.clone()));
        assert_eq!(h.undo(&a), None);
        assert_eq!(h.redo(&a), Some(b.clone()));
        assert_eq!(h.redo(&b), Some(c.clone()));
        assert!(!h.can_redo());
        h.undo(&c);
        h.record(b.clone());
        assert!(!h.can_redo(), "a new edit drops the redo steps");
    }
}
