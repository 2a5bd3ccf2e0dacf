//! A canonical form of a SPIR-V module, for cache keys that should change only when the code
//! does: debug information (names, source text, line markers) is dropped and ids are renumbered
//! in order of first appearance. The compiler numbers ids before its dead-code passes, so code
//! that is compiled and then removed (another sampler's branch, say) shifts the ids of
//! everything after it; two modules with equal canonical forms execute the same instructions.
use rspirv::binary::Assemble;
use rspirv::dr::{Instruction, Operand};
use rspirv::spirv::Op;
use std::collections::HashMap;

/// Whether `inst` only describes the source (never changes what runs).
fn is_debug(inst: &Instruction) -> bool {
    matches!(
        inst.class.opcode,
        Op::Line | Op::NoLine | Op::Source | Op::SourceContinued | Op::SourceExtension
    ) | matches!(
        inst.class.opcode,
        Op::Name | Op::MemberName | Op::String | Op::ModuleProcessed
    )
}

/// The canonical words of `words`, or `None` if they do not parse as SPIR-V.
pub fn canonical_words(words: &[u32]) -> Option<Vec<u32>> {
    let mut m = rspirv::dr::load_words(words).ok()?;
    m.debug_string_source.clear();
    m.debug_names.clear();
    m.debug_module_processed.clear();
    for f in &mut m.functions {
        for b in &mut f.blocks {
            b.instructions.retain(|i| !is_debug(i));
        }
    }
    m.types_global_values.retain(|i| !is_debug(i));
    let mut ids: HashMap<u32, u32> = HashMap::new();
    let mut renumber = |id: &mut u32| {
        let next = ids.len() as u32 + 1;
        *id = *ids.entry(*id).or_insert(next);
    };
    for inst in m.all_inst_iter_mut() {
        if let Some(t) = inst.result_type.as_mut() {
            renumber(t);
        }
        if let Some(r) = inst.result_id.as_mut() {
            renumber(r);
        }
        for op in &mut inst.operands {
            match op {
                Operand::IdRef(id) | Operand::IdScope(id) | Operand::IdMemorySemantics(id) => {
                    renumber(id)
                }
                _ => {}
            }
        }
    }
    let bound = ids.len() as u32 + 1;
    if let Some(h) = m.header.as_mut() {
        h.bound = bound;
        h.generator = 0;
    }
    Some(m.assemble())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn module(name: &str) -> Vec<u32> {
        crate::spirv(name).expect("compiled shader")
    }

    /// Adds `shift` to every id (result, type and operand ids) and to the bound.
    fn shifted(words: &[u32], shift: u32) -> Vec<u32> {
        let mut m = rspirv::dr::load_words(words).expect("parses");
        for inst in m.all_inst_iter_mut() {
            inst.result_type = inst.result_type.map(|t| t + shift);
            inst.result_id = inst.result_id.map(|r| r + shift);
            for op in &mut inst.operands {
                if let Operand::IdRef(id) | Operand::IdScope(id) | Operand::IdMemorySemantics(id) =
                    op
                {
                    *id += shift;
                }
            }
        }
        if let Some(h) = m.header.as_mut() {
            h.bound += shift;
        }
        m.assemble()
    }

    #[test]
    fn renumbered_ids_and_dropped_names_keep_the_form() {
        let w = module("trace/trace_sobol");
        let c = canonical_words(&w).expect("parses");
        assert_eq!(canonical_words(&shifted(&w, 1000)), Some(c.clone()));
        let mut m = rspirv::dr::load_words(&w).expect("parses");
        assert!(!m.debug_names.is_empty(), "the shaders carry debug names");
        m.debug_names.clear();
        assert_eq!(canonical_words(&m.assemble()), Some(c));
    }

    #[test]
    fn different_code_has_a_different_form() {
        // The two variants differ only in one constant (the sampler kind).
        let a = canonical_words(&module("trace/trace_sobol")).expect("parses");
        let b = canonical_words(&module("trace/trace_blocknet")).expect("parses");
        assert_ne!(a, b);
    }

    #[test]
    fn garbage_is_not_a_module() {
        assert_eq!(canonical_words(&[1, 2, 3]), None);
    }
}
