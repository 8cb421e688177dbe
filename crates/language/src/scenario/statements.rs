//! What the loader hands to analysis and to families, in a module of its
//! own so that the loader, the analyser and the families import it rather
//! than each other.

use crate::diagnostics::{Diag, SourceMap};
use crate::syntax::ast;

/// A scenario that could not be loaded: all its diagnostics and the sources
/// they point into.
#[derive(Debug)]
pub struct LoadFailure {
    pub sources: SourceMap,
    pub diags: Vec<Diag>,
}

/// A statement and whether it comes from the main file.
#[derive(Clone, Debug)]
pub struct SourcedStmt {
    pub stmt: ast::Stmt,
    pub in_main_file: bool,
}
