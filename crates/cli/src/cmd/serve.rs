//! `holey serve`: the interactive modeler in the browser.

use crate::output::outln;
use std::net::IpAddr;
use std::path::PathBuf;

use anyhow::{Context, Result};
use holey_serve::{Config, Server};

use crate::error::bad_input;

#[derive(clap::Args)]
#[command(after_help = "\
Serves the modeler and prints its address with an access token:
  holey serve: listening on http://127.0.0.1:PORT/?token=HEX
Open that URL. One session is shared by every tab; it is saved after every
change in the state directory and restored at the next start.

Access: every request must name this server in its Host header (localhost,
127.0.0.1, [::1] or the --host address, with this port or none; any IP
address when bound to 0.0.0.0 or ::); any other Host is refused (403), so a
web site whose domain name is pointed at this machine (DNS rebinding)
cannot drive the modeler. Every request must also carry the token, which
is new at every start (192 bits from the operating system's random
source): the page opened with ?token= keeps it in a cookie (HttpOnly,
SameSite=Strict) for its later requests, and scripts send the header
`Authorization: token HEX` or add ?token=HEX. Without it: 403. --token or
HOLEY_TOKEN fixes the token (for tests and tools); the environment
variable keeps it out of the process list other users can read.

The browser front end is built into the binary: `cargo build` runs npm
(web/) when web/dist is missing or older than its sources, and embeds
it, so the modeler is served from any directory and from an installed
or copied binary. --web DIR serves a front end from disk instead, for
front-end development (`npm --prefix web run dev` rebuilds it).

Examples:
  holey serve
  holey serve --port 0 --state-dir /tmp/holey-session --open
  HOLEY_TOKEN=fixed-token-for-my-tests holey serve --port 0
  curl -H 'Authorization: token HEX' 'http://127.0.0.1:PORT/api/export?format=obj'")]
pub struct Args {
    /// Port to listen on; 0 picks a free one.
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// Address to bind. Anything but loopback exposes the modeler (and
    /// the files it can write) to the network.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: IpAddr,
    /// Open the modeler (the URL with the token) in the default browser.
    #[arg(long)]
    pub open: bool,
    /// Fixed access token instead of a random one, for tests and tools
    /// (letters, digits, - . _ ~) [env: HOLEY_TOKEN].
    #[arg(long, value_name = "TOKEN")]
    pub token: Option<String>,
    /// Where the session is saved [default: $XDG_STATE_HOME/holey or ~/.local/state/holey].
    #[arg(long)]
    pub state_dir: Option<PathBuf>,
    /// Serve the front end from this folder (a built web/dist) instead of
    /// the copy embedded in the binary: for front-end development.
    #[arg(long)]
    pub web: Option<PathBuf>,
    /// Largest upload in MiB.
    #[arg(long, default_value_t = 256)]
    pub max_upload: usize,
}

fn default_state_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("XDG_STATE_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(d).join("holey");
    }
    if let Some(h) = std::env::var_os("HOME").filter(|h| !h.is_empty()) {
        return PathBuf::from(h).join(".local/state/holey");
    }
    PathBuf::from(".holey-session")
}

pub fn run(args: Args) -> Result<()> {
    if args.max_upload == 0 {
        return Err(bad_input("--max-upload must be at least 1 MiB"));
    }
    let web_dir = match args.web {
        Some(d) if d.join("index.html").is_file() => Some(d),
        Some(d) => {
            return Err(bad_input(format!(
                "{}: no index.html there (build the front end with `npm --prefix web run build`)",
                d.display()
            )));
        }
        None => None,
    };
    if !args.host.is_loopback() {
        eprintln!(
            "warning: binding {} makes the modeler reachable from the network over plain HTTP; the access token keeps out whoever lacks it, but anyone who can see the traffic can read it and edit the session",
            args.host
        );
    }
    if web_dir.is_none() && !holey_serve::embedded::is_present() {
        eprintln!(
            "note: this binary was built without the front end (npm was missing); install Node.js with npm and rebuild, or pass --web DIR"
        );
    }
    // clap's env feature is not enabled for the workspace, so the variable
    // is read here; the flag wins over it.
    let (token, source) = match args.token {
        Some(t) => (Some(t), "--token"),
        None => (
            std::env::var("HOLEY_TOKEN").ok().filter(|t| !t.is_empty()),
            "HOLEY_TOKEN",
        ),
    };
    if let Some(t) = &token {
        holey_serve::auth::check_token(t).map_err(|e| bad_input(format!("{source}: {e}")))?;
        if t.len() < 16 {
            eprintln!(
                "warning: {source} is {} characters long and can be guessed; without it a random 48-character token is made",
                t.len()
            );
        }
    }
    let config = Config {
        host: args.host,
        port: args.port,
        state_dir: args.state_dir.unwrap_or_else(default_state_dir),
        web_dir,
        max_upload: args.max_upload.saturating_mul(1 << 20),
        token,
        ..Config::default()
    };
    let (server, note) = Server::bind(config).context("holey serve")?;
    let url = server.url()?;
    eprintln!("{note}");
    outln!("holey serve: listening on {url}")?;
    if args.open {
        // Best effort: a machine without a desktop keeps serving.
        if let Err(e) = std::process::Command::new("xdg-open").arg(&url).spawn() {
            eprintln!("note: could not open a browser ({e}); open {url} yourself");
        }
    }
    server.run()?;
    Ok(())
}
