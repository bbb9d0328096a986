//! Large ordinary scene files, written in memory: the loader's linearity test
//! (`tests/hostile_input.rs`) and its bench (`benches/loader.rs`) include this file by path,
//! so that both time the same files.

/// `n` spheres, each with a radius, a translation and a diffuse BSDF: one per line, or all
/// on one line (`one_line`).
pub fn spheres(n: usize, one_line: bool) -> String {
    let sep = if one_line { " " } else { "\n" };
    let mut xml = String::from("<scene version=\"3.0.0\">");
    for i in 0..n {
        xml.push_str(sep);
        xml.push_str(&format!(
            "<shape type=\"sphere\"><float name=\"radius\" value=\"0.01\"/>\
             <transform name=\"to_world\"><translate x=\"{i}\"/></transform>\
             <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>"
        ));
    }
    xml.push_str(sep);
    xml.push_str("</scene>");
    xml
}

/// `n` `<default>` parameters, each used once (a sphere's radius).
pub fn defaults(n: usize) -> String {
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    for i in 0..n {
        xml.push_str(&format!("<default name=\"r{i}\" value=\"0.{i}1\"/>\n"));
    }
    for i in 0..n {
        xml.push_str(&format!(
            "<shape type=\"sphere\"><float name=\"radius\" value=\"$r{i}\"/></shape>\n"
        ));
    }
    xml.push_str("</scene>");
    xml
}

/// `n` top-level `<bsdf type="diffuse"/>`, one per line.
pub fn bsdfs(n: usize) -> String {
    format!(
        "<scene version=\"3.0.0\">\n{}</scene>",
        "<bsdf type=\"diffuse\"/>\n".repeat(n)
    )
}
