//! The parameters of one plugin element: typed values read from its property children,
//! with every lookup recorded so that a parameter nobody asked for is reported as unknown
//! (Mitsuba 3 does the same with its "unreferenced property" check).

use super::context::{Ctx, Res};
use super::spectrum::{Spectrum, SpectrumUse};
use super::transform::{check_attrs, read_transform, xyz};
use super::tree::Elem;
use super::values::{parse_bool, parse_float, parse_int, parse_triple};
use crate::description::Colour;
use crate::param_defs::generate::ParamSource;
use crate::param_defs::{
    self, BoolParam, ChoiceParam, ColourParam, FloatParam, IntParam, PluginParams,
};
use crate::scene_error::SceneErrorKind;
use glam::{Mat4, Vec3};
use std::collections::HashMap;

/// One parsed property value.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
    Int(i64),
    Float(f32),
    Bool(bool),
    Str(String),
    Rgb(Vec3),
    Spectrum(Spectrum),
    Vec3(Vec3),
    Transform(Mat4),
}

struct Prop<'a> {
    name: String,
    value: Value,
    elem: &'a Elem,
    used: bool,
}

/// Tags of nested objects (plugins and references).
pub(crate) const OBJECT_TAGS: &[&str] = &[
    "integrator",
    "sensor",
    "sampler",
    "film",
    "rfilter",
    "shape",
    "bsdf",
    "emitter",
    "texture",
    "ref",
];

/// Tags Mitsuba knows that this loader does not support.
const UNSUPPORTED_TAGS: &[&str] = &["medium", "phase", "volume", "path", "alias"];

// Textures are nested objects: a BSDF takes them out of `objects` by their `name`
// (`loader/texture.rs`); anywhere else they are refused as objects are.

/// The parameters and nested objects of a plugin element.
pub(crate) struct Props<'c, 'a> {
    ctx: &'c Ctx<'a>,
    /// The plugin element.
    elem: &'a Elem,
    plugin: String,
    /// The plugin's parameter definitions, if it has a table (every name looked up must
    /// be in it).
    defs: Option<&'static PluginParams>,
    props: Vec<Prop<'a>>,
    /// Index of each parameter name in `props` (a plugin may have many parameters).
    index: HashMap<String, usize>,
    /// Nested plugin and `ref` elements, in file order.
    pub objects: Vec<&'a Elem>,
}

impl<'c, 'a> Props<'c, 'a> {
    /// Reads the children of plugin element `e`, whose category is `e.tag`.
    pub fn new(ctx: &'c Ctx<'a>, e: &'a Elem) -> Res<Self> {
        let plugin = format!("{} \"{}\"", e.tag, e.attr("type").unwrap_or(""));
        let defs = param_defs::plugin(&e.tag, e.attr("type").unwrap_or(""));
        let mut out = Self {
            ctx,
            elem: e,
            plugin,
            defs,
            props: Vec::new(),
            index: HashMap::new(),
            objects: Vec::new(),
        };
        for c in &e.children {
            if OBJECT_TAGS.contains(&c.tag.as_str()) {
                out.objects.push(c);
                continue;
            }
            let value = read_value(ctx, c)?;
            let name = c.attr("name").unwrap_or("").to_string();
            if out.index.insert(name.clone(), out.props.len()).is_some() {
                return Err(ctx.err(c, SceneErrorKind::DuplicateParameter(name)));
            }
            out.props.push(Prop {
                name,
                value,
                elem: c,
                used: false,
            });
        }
        Ok(out)
    }

    /// Whether parameter `name` is given (without marking it used).
    pub fn has(&self, name: &str) -> bool {
        self.index.contains_key(name)
    }

    /// Looks up `name`, marking it used; returns its value and element.
    pub fn raw(&mut self, name: &str) -> Option<(Value, &'a Elem)> {
        // A programming error, not a scene's: the code reads a name its table lacks (so the
        // docs, tested against the tables, would miss it).
        assert!(
            self.defs
                .is_none_or(|d| d.params.iter().any(|p| p.name() == name)),
            "{} reads \"{name}\", which its table in param_defs does not define",
            self.plugin
        );
        let p = &mut self.props[*self.index.get(name)?];
        p.used = true;
        Some((p.value.clone(), p.elem))
    }

    /// A wrong-type error for parameter `name` given by element `e`.
    pub fn wrong(
        &self,
        e: &Elem,
        name: &str,
        expected: &'static str,
    ) -> crate::scene_error::SceneError {
        self.ctx.err(
            e,
            SceneErrorKind::WrongType {
                name: name.to_string(),
                expected,
                found: e.tag.clone(),
            },
        )
    }

    /// An error about the value of parameter `name` (or the plugin, if it is absent).
    pub fn invalid(&self, name: &str, owner: &Elem, msg: &str) -> crate::scene_error::SceneError {
        let e = self.index.get(name).map_or(owner, |&i| self.props[i].elem);
        self.ctx
            .err(e, SceneErrorKind::InvalidValue(format!("\"{name}\" {msg}")))
    }

    /// Integer parameter `d`: its value, checked, or its default.
    pub fn get_int(&mut self, d: &IntParam) -> Res<i64> {
        self.get_int_or(d, d.default)
    }

    /// Integer parameter `d`, checked, or `default` (a default that depends on another
    /// parameter).
    pub fn get_int_or(&mut self, d: &IntParam, default: i64) -> Res<i64> {
        Ok(self.int_in(d.name, d.min, d.max)?.unwrap_or(default))
    }

    /// Float parameter `d`: its value checked into `T`, or its default.
    pub fn get_float<T: Copy>(&mut self, d: &FloatParam<T>) -> Res<T> {
        match self.float(d.name)? {
            None => Ok(d.default),
            Some(v) => (d.accept)(v).map_err(|m| self.invalid(d.name, self.elem, &m)),
        }
    }

    /// Float parameter `d` checked into `T`, if the scene gives it (a default that depends
    /// on another parameter, or a required parameter).
    pub fn get_float_opt<T: Copy>(&mut self, d: &FloatParam<T>) -> Res<Option<T>> {
        match self.float(d.name)? {
            None => Ok(None),
            Some(v) => (d.accept)(v)
                .map(Some)
                .map_err(|m| self.invalid(d.name, self.elem, &m)),
        }
    }

    /// Integer parameter `d`, checked, if the scene gives it.
    pub fn get_int_opt(&mut self, d: &IntParam) -> Res<Option<i64>> {
        self.int_in(d.name, d.min, d.max)
    }

    /// Boolean parameter `d`: its value or its default.
    pub fn get_bool(&mut self, d: &BoolParam) -> Res<bool> {
        Ok(self.bool(d.name)?.unwrap_or(d.default))
    }

    /// String parameter `d`: one of its choices (given in any case), or its default.
    pub fn get_choice(&mut self, d: &ChoiceParam) -> Res<&'static str> {
        let Some(v) = self.string(d.name)? else {
            return Ok(d.default);
        };
        let v = v.to_ascii_lowercase();
        match d.choices.iter().find(|c| **c == v) {
            Some(c) => Ok(c),
            None => Err(self.invalid(
                d.name,
                self.elem,
                &format!("\"{v}\" is not {}", d.choices.join(" or ")),
            )),
        }
    }

    /// A float (an `<integer>` is accepted too).
    pub fn float(&mut self, name: &str) -> Res<Option<f32>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Float(v), _)) => Ok(Some(v)),
            Some((Value::Int(v), _)) => Ok(Some(v as f32)),
            Some((_, e)) => Err(self.wrong(e, name, "a <float>")),
        }
    }

    /// An integer.
    pub fn int(&mut self, name: &str) -> Res<Option<(i64, &'a Elem)>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Int(v), e)) => Ok(Some((v, e))),
            Some((_, e)) => Err(self.wrong(e, name, "an <integer>")),
        }
    }

    /// An integer in `lo..=hi`.
    pub fn int_in(&mut self, name: &str, lo: i64, hi: i64) -> Res<Option<i64>> {
        match self.int(name)? {
            None => Ok(None),
            Some((v, _)) if (lo..=hi).contains(&v) => Ok(Some(v)),
            Some((v, e)) => Err(self.ctx.err(
                e,
                SceneErrorKind::InvalidValue(format!("\"{name}\" = {v} is outside [{lo}, {hi}]")),
            )),
        }
    }

    /// A boolean.
    pub fn bool(&mut self, name: &str) -> Res<Option<bool>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Bool(v), _)) => Ok(Some(v)),
            Some((_, e)) => Err(self.wrong(e, name, "a <boolean>")),
        }
    }

    /// A string.
    pub fn string(&mut self, name: &str) -> Res<Option<String>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Str(v), _)) => Ok(Some(v)),
            Some((_, e)) => Err(self.wrong(e, name, "a <string>")),
        }
    }

    /// A reflectance-like colour: `<rgb>`, a `<spectrum>` (converted as a reflectance),
    /// or a `<float>`/`<integer>` used for all three channels.
    pub fn rgb(&mut self, name: &str) -> Res<Option<Vec3>> {
        self.colour(name, SpectrumUse::Reflectance)
    }

    /// Colour parameter `d` (as [`Props::rgb`]) checked into a [`Colour`], or its default.
    pub fn get_rgb(&mut self, d: &ColourParam) -> Res<Colour> {
        let v = self.rgb(d.name)?.unwrap_or(Vec3::splat(d.default));
        Colour::named(d.name, v).map_err(|i| self.invalid(d.name, self.elem, &i.message))
    }

    /// A colour as [`Props::rgb`], with a `<spectrum>` converted for `usage`.
    pub fn colour(&mut self, name: &str, usage: SpectrumUse) -> Res<Option<Vec3>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Rgb(v), _)) => Ok(Some(v)),
            Some((Value::Spectrum(s), _)) => Ok(Some(s.to_rgb(usage))),
            Some((Value::Float(v), _)) => Ok(Some(Vec3::splat(v))),
            Some((Value::Int(v), _)) => Ok(Some(Vec3::splat(v as f32))),
            Some((_, e)) => Err(self.wrong(e, name, "an <rgb>, a <spectrum> or a <float>")),
        }
    }

    /// A `<point>` or `<vector>`.
    pub fn point(&mut self, name: &str) -> Res<Option<Vec3>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Vec3(v), _)) => Ok(Some(v)),
            Some((_, e)) => Err(self.wrong(e, name, "a <point>")),
        }
    }

    /// A `<transform>`.
    pub fn transform(&mut self, name: &str) -> Res<Option<Mat4>> {
        match self.raw(name) {
            None => Ok(None),
            Some((Value::Transform(v), _)) => Ok(Some(v)),
            Some((_, e)) => Err(self.wrong(e, name, "a <transform>")),
        }
    }

    /// Errors on the first parameter that no lookup asked for.
    pub fn finish(self) -> Res<()> {
        match self.props.iter().find(|p| !p.used) {
            None => Ok(()),
            Some(p) => Err(self.ctx.err(
                p.elem,
                SceneErrorKind::UnknownParameter {
                    plugin: self.plugin.clone(),
                    name: p.name.clone(),
                },
            )),
        }
    }
}

/// The loader's reading of a plugin's generated parameter struct (`param_defs::generate`):
/// each value through [`Props`], errors located as its own `get_*` locate them.
impl ParamSource for Props<'_, '_> {
    type Error = crate::scene_error::SceneError;

    fn int(&mut self, d: &IntParam) -> Res<i64> {
        self.get_int(d)
    }

    fn int_or(&mut self, d: &IntParam, default: i64) -> Res<i64> {
        self.get_int_or(d, default)
    }

    fn float(&mut self, d: &FloatParam<f32>) -> Res<f32> {
        self.get_float(d)
    }

    fn boolean(&mut self, d: &BoolParam) -> Res<bool> {
        self.get_bool(d)
    }

    fn invalid(&self, i: crate::invalid::Invalid) -> Self::Error {
        Props::invalid(self, i.param, self.elem, &i.message)
    }
}

/// Parses one property element.
pub(crate) fn read_value(ctx: &Ctx, c: &Elem) -> Res<Value> {
    let tag = c.tag.as_str();
    let malformed = |m: String| ctx.err(c, SceneErrorKind::Malformed(m));
    let simple = |c: &Elem| -> Res<String> {
        check_attrs(ctx, c, &["name", "value"], &["name", "value"])?;
        no_children(ctx, c)?;
        Ok(c.attr("value").unwrap_or("").to_string())
    };
    let name = c.attr("name").unwrap_or("");
    if name.starts_with('_') {
        return Err(ctx.err(
            c,
            SceneErrorKind::InvalidValue(format!(
                "parameter name \"{name}\": leading underscores are reserved"
            )),
        ));
    }
    Ok(match tag {
        "integer" => Value::Int(parse_int(&simple(c)?).map_err(malformed)?),
        "float" => Value::Float(parse_float(&simple(c)?).map_err(malformed)?),
        "boolean" => Value::Bool(parse_bool(&simple(c)?).map_err(malformed)?),
        "string" => Value::Str(simple(c)?),
        "rgb" => Value::Rgb(parse_triple(&simple(c)?, "rgb").map_err(malformed)?),
        "spectrum" => {
            if c.attr("filename").is_some() {
                return Err(ctx.err(
                    c,
                    SceneErrorKind::Unsupported(
                        "<spectrum filename=…> (spectral data files)".into(),
                    ),
                ));
            }
            Value::Spectrum(Spectrum::parse(&simple(c)?).map_err(malformed)?)
        }
        "point" | "vector" => {
            check_attrs(ctx, c, &["name", "value", "x", "y", "z"], &["name"])?;
            no_children(ctx, c)?;
            if c.attr("value").is_none() {
                check_attrs(ctx, c, &["name", "x", "y", "z"], &["x", "y", "z"])?;
            }
            Value::Vec3(xyz(ctx, c, &["name"], 0.0)?)
        }
        "transform" => Value::Transform(read_transform(ctx, c)?),
        t if UNSUPPORTED_TAGS.contains(&t) => {
            return Err(ctx.err(c, SceneErrorKind::Unsupported(format!("<{t}> elements"))))
        }
        "lookat" | "matrix" | "translate" | "rotate" | "scale" => {
            return Err(ctx.err(
                c,
                SceneErrorKind::Misplaced(format!("<{tag}> outside a <transform>")),
            ))
        }
        "scene" | "default" => {
            return Err(ctx.err(
                c,
                SceneErrorKind::Misplaced(format!("<{tag}> inside another element")),
            ))
        }
        t => return Err(ctx.err(c, SceneErrorKind::UnknownElement(t.to_string()))),
    })
}

fn no_children(ctx: &Ctx, c: &Elem) -> Res<()> {
    match c.children.first() {
        None => Ok(()),
        Some(k) => Err(ctx.err(
            k,
            SceneErrorKind::Misplaced(format!("<{}> inside a property <{}>", k.tag, c.tag)),
        )),
    }
}
