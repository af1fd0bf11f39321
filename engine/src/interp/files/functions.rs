//! The file procedures and `ISFILE` run on the interpreter: arguments evaluated, the file found
//! in the pending changes or the store, the error code and results written to the program's
//! variables.

use std::sync::Arc;

use super::path::{self, FileName, NameError};
use super::{Files, Pending};
use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::eval::value::Value;
use crate::interp::modal::assign;
use crate::interp::{Interpreter, Programs};
use crate::lang::{Expr, VarType};
use crate::machine_data::MachineConfig;
use crate::programs::Kind;

/// A file's text as the program sees it: a pending change or the stored text.
enum View<'a> {
    Pending(&'a str),
    Stored(Arc<str>),
}

impl std::ops::Deref for View<'_> {
    type Target = str;
    fn deref(&self) -> &str {
        match self {
            View::Pending(t) => t,
            View::Stored(t) => t,
        }
    }
}

/// The text of file `f`: `Ok(None)` if there is none, `Err(code)` if it cannot be read.
fn view<'a>(files: &'a Files, programs: &Programs, f: &FileName) -> Result<Option<View<'a>>, i64> {
    if let Some(p) = files.pending.get(&f.name) {
        return Ok(p.text.as_deref().map(View::Pending));
    }
    match programs.file(&f.name, f.dir.as_ref()) {
        None => Ok(None),
        Some(p) => p.raw_text().map(|t| Some(View::Stored(t))).map_err(|_| super::OTHER),
    }
}

/// The error code of a name that names no file, for a function that writes (`write`) or reads.
fn name_code(e: NameError, write: bool) -> i64 {
    match e {
        NameError::PathNotPermitted => super::PATH_NOT_PERMITTED,
        NameError::PathNotFound => super::PATH_NOT_FOUND,
        NameError::WrongType => super::WRONG_TYPE,
        NameError::BadName if write => super::PATH_NOT_PERMITTED,
        NameError::BadName => super::FILE_NOT_FOUND,
    }
}

impl Interpreter {
    /// Evaluates `e` with the channel's view.
    fn value_of(&self, e: &Expr, cfg: &MachineConfig, line: u32) -> Result<Value, Alarm> {
        let sys = sys_view!(self, cfg);
        eval(e, &Ctx { vars: &self.vars, sys: &sys }, line)
    }

    /// Writes `value` to the variable `target` names (a user variable, an element, `R<n>`).
    fn set_out(&mut self, target: &Expr, value: Value, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        let (name, indices) = match target {
            Expr::Var { name, indices } if !name.starts_with('$') => (name.as_str(), indices.clone()),
            Expr::RParam(n) => ("R", vec![(**n).clone()]),
            _ => return Err(Alarm::syntax(line, "a file function's result needs a variable")),
        };
        let expr = match value {
            Value::Str(s) => Expr::Str(s),
            Value::Bool(b) => Expr::Bool(b),
            v => Expr::Number(v.as_f64().unwrap_or(0.0)),
        };
        let sys = sys_view!(self, cfg);
        assign(name, &indices, &expr, cfg, &mut self.vars, &sys, line).map(|_| ())
    }

    /// `ISFILE("file")`: whether the file exists (a name that names no file: FALSE).
    pub(in crate::interp) fn isfile(
        &self,
        args: &[Expr],
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
    ) -> Result<bool, Alarm> {
        let [file] = args else { return Err(Alarm::syntax(line, "ISFILE takes one file name")) };
        let spec = self.value_of(file, cfg, line)?.as_text();
        Ok(path::parse(&spec).is_ok_and(|f| matches!(view(&self.files, programs, &f), Ok(Some(_)))))
    }

    /// Runs the file procedure `name` (one of [`super::PROCEDURES`]) of the block at `line`.
    pub(in crate::interp) fn file_procedure(
        &mut self,
        name: &str,
        args: &[Expr],
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
    ) -> Result<(), Alarm> {
        let want = match name {
            "WRITE" => 3,
            "READ" => 5,
            "DELETE" => 2,
            _ => 3,
        };
        if args.len() != want {
            return Err(Alarm::syntax(line, &format!("{name} takes {want} arguments")));
        }
        let spec = self.value_of(&args[1], cfg, line)?.as_text();
        let writes = matches!(name, "WRITE" | "DELETE");
        let code = match path::parse(&spec) {
            Err(e) => name_code(e, writes),
            Ok(f) if writes && !matches!(f.kind, Kind::Main | Kind::Sub) => super::WRONG_TYPE,
            Ok(f) => match name {
                "WRITE" => {
                    let text = self.value_of(&args[2], cfg, line)?.as_text();
                    self.write_line(&f, &text, cfg, programs, line)?
                }
                "DELETE" => self.delete_file(&f, programs),
                "READ" => self.read_lines(&f, &args[2..], cfg, programs, line)?,
                _ => match view(&self.files, programs, &f) {
                    Err(code) => code,
                    Ok(None) => super::FILE_NOT_FOUND,
                    Ok(Some(text)) => {
                        let (size, stamp) = (text.len() as i64, self.files.stamp(&f.name));
                        let stat = "rwxsd";
                        let result = match name {
                            "FILEDATE" => Value::Str(super::date(stamp)),
                            "FILETIME" => Value::Str(super::time(stamp)),
                            "FILESIZE" => Value::Int(size),
                            "FILESTAT" => Value::Str(stat.into()),
                            _ => Value::Str(format!("{stat} {size} {} {}", super::date(stamp), super::time(stamp))),
                        };
                        self.set_out(&args[2], result, cfg, line)?;
                        super::OK
                    }
                },
            },
        };
        self.set_out(&args[0], Value::Int(code), cfg, line)
    }

    /// WRITE: appends `text` and a line feed to the file, creating it; its error code.
    fn write_line(
        &mut self,
        f: &FileName,
        text: &str,
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
    ) -> Result<i64, Alarm> {
        if self.level().is_some_and(|l| l.within(&f.name)) {
            return Ok(super::FILE_IN_USE);
        }
        let limit_kb =
            match crate::interp::eval::machine_data::read(&self.stored, cfg, "$MN_LEN_PROTOCOL_FILE", &[], line) {
                Some(Ok(v)) => v.as_i64().unwrap_or(1),
                _ => 1,
            };
        let limit = usize::try_from(limit_kb).unwrap_or(0).saturating_mul(1024);
        let current = match view(&self.files, programs, f) {
            Err(code) => return Ok(code),
            Ok(v) => v.map_or(0, |t| t.len()),
        };
        if current + text.len() + 1 > limit {
            return Ok(super::FILE_FULL);
        }
        if self.files.budget.is_some_and(|b| self.files.total_bytes(programs) + text.len() + 1 > b) {
            return Ok(super::NO_RESOURCES);
        }
        if !matches!(self.files.pending.get(&f.name), Some(Pending { text: Some(_), .. })) {
            // The first line since the store last took the changes: start from the stored text.
            let stored = programs.file(&f.name, f.dir.as_ref());
            // A new file goes where its path says in a store of directories; the session's
            // flat store (programs PUT over REST, archives) has one program per name.
            let new_dir = || programs.main_dir().and(f.dir.clone());
            let dir = stored.map_or_else(new_dir, |p| p.dir().cloned());
            let base = match stored.filter(|_| !self.files.pending.contains_key(&f.name)) {
                Some(p) => p.raw_text().map_err(|_| ()).map(|t| t.to_string()).unwrap_or_default(),
                None => String::new(),
            };
            self.files.pending.insert(f.name.clone(), Pending { dir, kind: f.kind.clone(), text: Some(base) });
        }
        if let Some(Pending { text: Some(body), .. }) = self.files.pending.get_mut(&f.name) {
            body.reserve(text.len() + 1);
            body.push_str(text);
            body.push('\n');
        }
        let now = self.files.now(cfg.ipo_cycle);
        self.files.stamps.insert(f.name.clone(), now);
        Ok(super::OK)
    }

    /// DELETE: removes the file; its error code.
    fn delete_file(&mut self, f: &FileName, programs: &Programs) -> i64 {
        match view(&self.files, programs, f) {
            Err(code) => return code,
            Ok(None) => return super::FILE_NOT_FOUND,
            Ok(Some(_)) => {}
        }
        if self.level().is_some_and(|l| l.within(&f.name)) {
            return super::FILE_IN_USE;
        }
        let dir = programs.file(&f.name, f.dir.as_ref()).and_then(|p| p.dir().cloned());
        self.files.pending.insert(f.name.clone(), Pending { dir, kind: f.kind.clone(), text: None });
        self.files.stamps.remove(&f.name);
        super::OK
    }

    /// READ(err, file, first, count, result[]): `count` lines from line `first` (1 = the first;
    /// 0 = the last `count` lines) into the STRING array; its error code.
    fn read_lines(
        &mut self,
        f: &FileName,
        args: &[Expr],
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
    ) -> Result<i64, Alarm> {
        let number = |this: &Self, e: &Expr| -> Result<i64, Alarm> {
            this.value_of(e, cfg, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))
        };
        let (first, count) = (number(self, &args[0])?, number(self, &args[1])?);
        let Expr::Var { name: array, indices } = &args[2] else {
            return Err(Alarm::syntax(line, "READ needs a STRING array for its result"));
        };
        let (len, max) = match self.vars.get(array) {
            Some(v) if indices.is_empty() => match v.ty {
                VarType::Str(n) => (v.data.len(), usize::from(n)),
                _ => return Err(Alarm::type_error(line, &format!("READ: {array} is no STRING array"))),
            },
            Some(_) => return Err(Alarm::syntax(line, "READ: the result is the array's name, without an index")),
            None => return Err(Alarm::unknown_name(line, array)),
        };
        let lines: Vec<String> = {
            let text = match view(&self.files, programs, f) {
                Err(code) => return Ok(code),
                Ok(None) => return Ok(super::FILE_NOT_FOUND),
                Ok(Some(t)) => t,
            };
            let all: Vec<&str> = text.lines().map(|l| l.strip_suffix('\r').unwrap_or(l)).collect();
            let n = all.len() as i64;
            if first < 0 || first > n || (first == 0 && n == 0) {
                return Ok(super::NO_SUCH_LINE);
            }
            if count < 1 || (first == 0 && count > n) || (first > 0 && first - 1 + count > n) {
                return Ok(super::RANGE_TOO_LARGE);
            }
            if count as usize > len {
                return Ok(super::ARRAY_TOO_SHORT);
            }
            let start = if first == 0 { n - count } else { first - 1 } as usize;
            // A line longer than the array's strings is cut to their length.
            all[start..start + count as usize].iter().map(|l| l.chars().take(max).collect()).collect()
        };
        for (i, text) in lines.into_iter().enumerate() {
            let target = Expr::Var { name: array.clone(), indices: vec![Expr::Number(i as f64)] };
            self.set_out(&target, Value::Str(text), cfg, line)?;
        }
        Ok(super::OK)
    }
}
