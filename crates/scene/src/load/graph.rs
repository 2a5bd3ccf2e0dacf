//! The node graph of the scene to render, checked before it is expanded.
//!
//! glTF requires the nodes to form disjoint strict trees. The loader draws a node once per
//! path from a root to it, so a node that is its own ancestor expands without end, and a node
//! listed twice (as a child, or by two parents) doubles its subtree at every level: a chain of
//! 40 such nodes is 2^40 instances in a file of a few kilobytes. Here every node of the scene
//! is visited once, in time and memory linear in the file, and the first violation is named.

use crate::SceneError;
use std::path::Path;

/// How a node was reached so far.
#[derive(Clone, Copy, PartialEq)]
enum Seen {
    No,
    Root,
    ChildOf(usize),
}

/// Checks the trees under the roots of `scene` (at most `max_depth` levels) and that no node
/// outside them adopts one of their nodes. Returns the scene's nodes, each once.
pub(super) fn check(
    path: &Path,
    document: &gltf::Document,
    scene: &gltf::Scene,
    max_depth: usize,
) -> Result<Vec<usize>, SceneError> {
    let path = path.to_path_buf();
    let n = document.nodes().len();
    let mut seen = vec![Seen::No; n];
    let mut on_path = vec![false; n];
    for root in scene.nodes() {
        let node = root.index();
        if seen[node] != Seen::No {
            let scene = scene.index();
            return Err(SceneError::RootRepeated { path, scene, node });
        }
        seen[node] = Seen::Root;
    }
    let mut order = Vec::new();
    for root in scene.nodes() {
        order.push(root.index());
        on_path[root.index()] = true;
        let mut stack = vec![(root.index(), root.children())];
        while let Some((parent, children)) = stack.last_mut() {
            let parent = *parent;
            let Some(child) = children.next() else {
                on_path[parent] = false;
                stack.pop();
                continue;
            };
            let node = child.index();
            if on_path[node] {
                return Err(SceneError::NodeCycle { path, node });
            }
            if seen[node] != Seen::No {
                return Err(listed_again(path, scene.index(), node, seen[node], parent));
            }
            if stack.len() >= max_depth {
                return Err(SceneError::NodeDepth { path, max_depth });
            }
            seen[node] = Seen::ChildOf(parent);
            on_path[node] = true;
            order.push(node);
            stack.push((node, child.children()));
        }
    }
    // A node outside the scene that lists one of its nodes is a second parent too.
    for outside in document.nodes().filter(|p| seen[p.index()] == Seen::No) {
        for child in outside.children() {
            let node = child.index();
            if seen[node] != Seen::No {
                let parent = outside.index();
                return Err(listed_again(path, scene.index(), node, seen[node], parent));
            }
        }
    }
    Ok(order)
}

/// The error for `node` of `scene`, reached before as `seen`, listed again as a child of
/// `parent`.
fn listed_again(
    path: std::path::PathBuf,
    scene: usize,
    node: usize,
    seen: Seen,
    parent: usize,
) -> SceneError {
    match seen {
        Seen::ChildOf(first) if first == parent => SceneError::NodeRepeated { path, node, parent },
        Seen::ChildOf(first) => SceneError::NodeParents {
            path,
            node,
            parents: [first, parent],
        },
        Seen::Root | Seen::No => SceneError::RootWithParent {
            path,
            scene,
            node,
            parent,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks a document with `children[i]` as the children of node `i` and `roots` as the
    /// roots of its only scene.
    fn check_graph(children: &[&[usize]], roots: &[usize], max_depth: usize) -> String {
        let nodes: Vec<_> = children
            .iter()
            .map(|c| serde_json::json!({ "children": c }))
            .collect();
        let doc = serde_json::json!({
            "asset": { "version": "2.0" }, "scenes": [{ "nodes": roots }], "nodes": nodes
        });
        let gltf = gltf::Gltf::from_slice(&serde_json::to_vec(&doc).expect("json")).expect("doc");
        let scene = gltf.scenes().next().expect("scene");
        match check(Path::new("g"), &gltf.document, &scene, max_depth) {
            Ok(order) => format!("ok {order:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn trees_pass_and_each_node_is_listed_once() {
        assert_eq!(
            check_graph(&[&[1, 2], &[3], &[], &[], &[]], &[0, 4], 8),
            "ok [0, 1, 3, 2, 4]"
        );
        // Nodes outside the scene may be anything that does not touch it.
        assert_eq!(check_graph(&[&[], &[2], &[1]], &[0], 8), "ok [0]");
    }

    #[test]
    fn each_violation_names_its_node() {
        type Case<'a> = (&'a [&'a [usize]], &'a [usize], &'a str);
        let cases: [Case; 7] = [
            (
                &[&[0, 0, 0, 1], &[]],
                &[0, 1],
                "g: node 0 is its own ancestor",
            ),
            (&[&[1], &[2], &[0]], &[0], "g: node 0 is its own ancestor"),
            (
                &[&[2], &[2], &[]],
                &[0, 1],
                "g: node 2 has two parents, nodes 0 and 1",
            ),
            (
                &[&[1, 1], &[]],
                &[0],
                "g: node 1 is listed more than once among the children of node 0",
            ),
            (
                &[&[1], &[]],
                &[0, 1],
                "g: node 1 is a root of scene 0 and also a child of node 0",
            ),
            (
                &[&[]],
                &[0, 0],
                "g: node 0 is listed more than once among the roots of scene 0",
            ),
            // The second parent lies outside the scene.
            (
                &[&[1], &[], &[1]],
                &[0],
                "g: node 1 has two parents, nodes 0 and 2",
            ),
        ];
        for (children, roots, want) in cases {
            assert_eq!(
                check_graph(children, roots, 8),
                want,
                "{children:?} {roots:?}"
            );
        }
    }

    #[test]
    fn depth_is_bounded_before_expansion() {
        let chain: Vec<Vec<usize>> = (0..10).map(|i| vec![i + 1]).chain([vec![]]).collect();
        let chain: Vec<&[usize]> = chain.iter().map(Vec::as_slice).collect();
        assert!(check_graph(&chain, &[0], 11).starts_with("ok"));
        assert_eq!(
            check_graph(&chain, &[0], 10),
            "g: node hierarchy is deeper than 10 levels"
        );
    }
}
