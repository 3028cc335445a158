//! Reading the fields of a request.

use glam::DVec3;
use serde_json::Value;

use crate::ServeError;

pub(super) fn str_field<'a>(req: &'a Value, name: &str) -> Result<&'a str, ServeError> {
    req.get(name)
        .and_then(Value::as_str)
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a string")))
}

pub(super) fn num_field(req: &Value, name: &str) -> Result<f64, ServeError> {
    req.get(name)
        .and_then(Value::as_f64)
        .filter(|v| v.is_finite())
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a finite number")))
}

pub(super) fn index_field(req: &Value, name: &str) -> Result<usize, ServeError> {
    req.get(name)
        .and_then(Value::as_u64)
        .and_then(|v| usize::try_from(v).ok())
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a non-negative integer")))
}

pub(super) fn point_field(req: &Value) -> Result<DVec3, ServeError> {
    let bad = || ServeError::BadRequest("\"point\" must be [x, y, z] of finite numbers".into());
    let a = req.get("point").and_then(Value::as_array).ok_or_else(bad)?;
    if a.len() != 3 {
        return Err(bad());
    }
    let c = |i: usize| a[i].as_f64().filter(|v| v.is_finite()).ok_or_else(bad);
    Ok(DVec3::new(c(0)?, c(1)?, c(2)?))
}

pub(super) fn pair(req: &Value, name: &str) -> Result<[usize; 2], ServeError> {
    let bad = || ServeError::BadRequest(format!("\"{name}\" must be two non-negative integers"));
    let a = req.get(name).and_then(Value::as_array).ok_or_else(bad)?;
    let get = |i: usize| {
        a.get(i)
            .and_then(Value::as_u64)
            .and_then(|v| usize::try_from(v).ok())
            .ok_or_else(bad)
    };
    if a.len() != 2 {
        return Err(bad());
    }
    Ok([get(0)?, get(1)?])
}
