//! What the page's requests ask for: the query string decoded, a frame
//! (view, camera time, model, speed) read from it, and the fixture sped up.

use renderer::Model;
use std::collections::HashMap;

/// What a render request asks for: a declared view, at a camera time and
/// in a model, with the moving object's speed scaled.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Frame {
    pub(super) fixture: String,
    pub(super) view: String,
    pub(super) t: Option<f64>,
    /// The camera's proper time instead of `t` (a camera on a worldline).
    pub(super) tau: Option<f64>,
    pub(super) model: Option<Model>,
    pub(super) speed: f64,
}

pub(super) fn query(url: &str) -> HashMap<String, String> {
    let q = url.split_once('?').map_or("", |(_, q)| q);
    q.split('&')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (decode(k), decode(v)))
        .collect()
}

/// Percent-decoding of a query component (`+` is a space; a `%` not
/// followed by two hex digits stays as it is).
fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = b
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (b[i], hex) {
            (b'+', _) => out.push(b' '),
            (b'%', Some(v)) => {
                out.push(v);
                i += 2;
            }
            (c, _) => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn model_named(s: &str) -> Option<Model> {
    match s {
        "infinite" => Some(Model::INFINITE),
        "classical" => Some(Model::CLASSICAL),
        "relativistic" => Some(Model::RELATIVISTIC),
        _ => None,
    }
}

impl Frame {
    pub(super) fn of(q: &HashMap<String, String>) -> Result<Frame, String> {
        let get = |k: &str| q.get(k).ok_or_else(|| format!("missing {k}"));
        let number = |k: &str| -> Result<Option<f64>, String> {
            match q.get(k).filter(|v| !v.is_empty()) {
                None => Ok(None),
                Some(v) => v
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .map(Some)
                    .ok_or_else(|| format!("{k}={v}: not a number")),
            }
        };
        let model = match q.get("model").map(String::as_str) {
            None | Some("") | Some("view") => None,
            Some(m) => Some(
                model_named(m)
                    .ok_or_else(|| format!("model={m}: infinite, classical or relativistic"))?,
            ),
        };
        let (t, tau) = (number("t")?, number("tau")?);
        if t.is_some() && tau.is_some() {
            return Err(
                "give the camera time as t (lab time) or tau (proper time), not both".into(),
            );
        }
        Ok(Frame {
            fixture: get("fixture")?.clone(),
            view: get("view")?.clone(),
            t,
            tau,
            model,
            speed: number("speed")?.unwrap_or(1.0),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_are_decoded() {
        let q = query("/api/render?fixture=flange&view=frame%20920&t=1171.5&model=classical");
        assert_eq!(q["view"], "frame 920");
        let fr = Frame::of(&q).unwrap();
        assert_eq!(
            (fr.t, fr.model, fr.speed),
            (Some(1171.5), Some(Model::CLASSICAL), 1.0)
        );
        assert!(Frame::of(&query("/x?fixture=a&view=b&t=soon")).is_err());
        let tau = Frame::of(&query("/x?fixture=a&view=b&tau=2.5")).unwrap();
        assert_eq!((tau.t, tau.tau), (None, Some(2.5)));
        assert!(Frame::of(&query("/x?fixture=a&view=b&t=1&tau=2")).is_err());
        assert_eq!(decode("a+b%2Cc%zz"), "a b,c%zz");
    }
}
