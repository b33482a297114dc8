//! `pdr serve`: the development server.
//! May import: std and the server crates; not the `pdr` library, nor the other subcommands.
//!
//! Serves a static folder (the built site) over plain HTTP on localhost and over HTTPS on all
//! interfaces, so that a phone on the same network can open it: browsers expose DeviceMotion and
//! Geolocation only in a secure context. The HTTPS certificate is self-signed, generated on first
//! run with `rcgen` and kept outside the repository (in the user's data directory); it is
//! regenerated when the machine's LAN addresses change. The LAN URL is printed with a QR code.

use std::io::{ErrorKind, Read, Write};
use std::net::{IpAddr, TcpListener};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

/// Options of `pdr serve`.
#[derive(Debug, Clone)]
pub struct ServeOpts {
    /// Folder to serve (the built static site).
    pub root: PathBuf,
    /// Plain HTTP port, bound on localhost only.
    pub http_port: u16,
    /// HTTPS port, bound on all interfaces.
    pub https_port: u16,
    /// Where the self-signed certificate is kept (outside the repository).
    pub cert_dir: Option<PathBuf>,
}

/// MIME type for a file name.
pub fn mime(path: &Path) -> &'static str {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("html") | Some("htm") => "text/html; charset=utf-8",
        Some("js") | Some("mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("json") | Some("map") => "application/json",
        Some("webmanifest") => "application/manifest+json",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("ico") => "image/x-icon",
        Some("txt") | Some("csv") => "text/plain; charset=utf-8",
        Some("ts") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// Maps a request URL to a file below `root`, refusing anything that would leave it.
pub fn resolve(root: &Path, url: &str) -> Option<PathBuf> {
    let path = url.split(['?', '#']).next().unwrap_or("/");
    let decoded = percent_encoding::percent_decode_str(path)
        .decode_utf8()
        .ok()?;
    let mut out = root.to_path_buf();
    for comp in Path::new(decoded.trim_start_matches('/')).components() {
        match comp {
            Component::Normal(c) => out.push(c),
            Component::CurDir => {}
            _ => return None,
        }
    }
    if decoded.ends_with('/') || out.is_dir() {
        out.push("index.html");
    }
    Some(out)
}

fn default_cert_dir() -> PathBuf {
    let data = std::env::var_os("XDG_DATA_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".local/share")))
        .unwrap_or_else(std::env::temp_dir);
    data.join("pdr").join("cert")
}

fn lan_ips() -> Vec<IpAddr> {
    let mut ips: Vec<IpAddr> = local_ip_address::list_afinet_netifas()
        .map(|l| {
            l.into_iter()
                .map(|(_, ip)| ip)
                .filter(|ip| ip.is_ipv4() && !ip.is_loopback())
                .collect()
        })
        .unwrap_or_default();
    ips.sort();
    ips.dedup();
    ips
}

/// Loads the certificate from `dir`, or makes a new one when missing or when its names differ.
fn certificate(dir: &Path, names: &[String]) -> Result<(Vec<u8>, Vec<u8>), String> {
    let (cert_p, key_p, names_p) = (
        dir.join("cert.pem"),
        dir.join("key.pem"),
        dir.join("names.txt"),
    );
    let wanted = names.join("\n");
    if let (Ok(c), Ok(k), Ok(n)) = (
        std::fs::read(&cert_p),
        std::fs::read(&key_p),
        std::fs::read_to_string(&names_p),
    ) {
        if n == wanted {
            return Ok((c, k));
        }
    }
    let certified = rcgen::generate_simple_self_signed(names.to_vec())
        .map_err(|e| format!("cannot make a certificate: {e}"))?;
    let (c, k) = (
        certified.cert.pem().into_bytes(),
        certified.signing_key.serialize_pem().into_bytes(),
    );
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    std::fs::write(&cert_p, &c).map_err(|e| format!("{}: {e}", cert_p.display()))?;
    std::fs::write(&key_p, &k).map_err(|e| format!("{}: {e}", key_p.display()))?;
    std::fs::write(&names_p, wanted).map_err(|e| format!("{}: {e}", names_p.display()))?;
    eprintln!("made a self-signed certificate in {}", dir.display());
    Ok((c, k))
}

/// The longest request head read (request line and headers).
const MAX_HEAD: usize = 16 * 1024;

/// Answers one request on a connection and closes it. One request per connection
/// (`Connection: close`): the browser then never reuses a connection, which is where
/// tiny_http's keep-alive lost a response now and then (a module script stayed pending for
/// ever, about 1 page load in 40 in headless Chromium).
fn handle<S: Read + Write>(root: &Path, mut s: S) -> std::io::Result<()> {
    let mut head = Vec::with_capacity(1024);
    let mut chunk = [0u8; 4096];
    // Where the search for the blank line resumes: only what the last read added (and the
    // three bytes before it) is new.
    let mut searched = 0;
    while !head[searched..].windows(4).any(|w| w == b"\r\n\r\n") {
        searched = head.len().saturating_sub(3);
        if head.len() > MAX_HEAD {
            return respond(
                &mut s,
                "431 Request Header Fields Too Large",
                "text/plain",
                b"",
                false,
            );
        }
        let n = s.read(&mut chunk)?;
        if n == 0 {
            return Ok(());
        }
        head.extend_from_slice(&chunk[..n]);
    }
    let line = String::from_utf8_lossy(head.split(|&b| b == b'\r').next().unwrap_or_default());
    let mut parts = line.split(' ');
    let (method, target) = (parts.next().unwrap_or(""), parts.next().unwrap_or("/"));
    let head_only = method == "HEAD";
    if method != "GET" && !head_only {
        return respond(
            &mut s,
            "405 Method Not Allowed",
            "text/plain",
            b"GET or HEAD only",
            false,
        );
    }
    match resolve(root, target).and_then(|p| std::fs::read(&p).ok().map(|b| (p, b))) {
        Some((path, body)) => respond(&mut s, "200 OK", mime(&path), &body, head_only),
        None => respond(
            &mut s,
            "404 Not Found",
            "text/plain",
            b"not found",
            head_only,
        ),
    }
}

fn respond<S: Write>(
    s: &mut S,
    status: &str,
    content_type: &str,
    body: &[u8],
    head_only: bool,
) -> std::io::Result<()> {
    write!(
        s,
        "HTTP/1.1 {status}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\n\
         Cache-Control: no-cache\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    if !head_only {
        s.write_all(body)?;
    }
    s.flush()
}

/// Accepts connections for ever, each answered in its own thread (a client that stops reading
/// blocks only its own thread), over TLS when `tls` is given.
fn spawn(
    listener: TcpListener,
    root: Arc<PathBuf>,
    tls: Option<Arc<rustls::ServerConfig>>,
) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(stream) = stream else { continue };
            let (root, tls) = (Arc::clone(&root), tls.clone());
            std::thread::spawn(move || {
                let _ = stream.set_read_timeout(Some(Duration::from_secs(30)));
                let _ = stream.set_write_timeout(Some(Duration::from_secs(60)));
                let result = match tls {
                    None => handle(&root, &stream),
                    Some(cfg) => rustls::ServerConnection::new(cfg)
                        .map_err(std::io::Error::other)
                        .and_then(|conn| {
                            let mut tls = rustls::StreamOwned::new(conn, &stream);
                            handle(&root, &mut tls)?;
                            tls.conn.send_close_notify();
                            tls.flush()
                        }),
                };
                if let Err(e) = result {
                    // A phone refusing the self-signed certificate ends up here too.
                    if !matches!(
                        e.kind(),
                        ErrorKind::BrokenPipe | ErrorKind::ConnectionReset | ErrorKind::WouldBlock
                    ) {
                        eprintln!("pdr serve: {e}");
                    }
                }
            });
        }
    })
}

/// The TLS configuration from a PEM certificate and private key, with ring as the crypto
/// provider (see Cargo.toml for why ring).
fn tls_config(cert: &[u8], key: &[u8]) -> Result<Arc<rustls::ServerConfig>, String> {
    use rustls::pki_types::pem::PemObject;
    use rustls::pki_types::{CertificateDer, PrivateKeyDer};
    let certs = CertificateDer::pem_slice_iter(cert)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| format!("certificate: {e}"))?;
    if certs.is_empty() {
        return Err("certificate: none in the file".into());
    }
    let key = PrivateKeyDer::from_pem_slice(key).map_err(|e| format!("private key: {e}"))?;
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    rustls::ServerConfig::builder_with_provider(provider)
        .with_safe_default_protocol_versions()
        .map_err(|e| format!("TLS: {e}"))?
        .with_no_client_auth()
        .with_single_cert(certs, key)
        .map(Arc::new)
        .map_err(|e| format!("certificate: {e}"))
}

/// The QR code of `url` for a terminal: two rows of modules per line of text (Unicode half
/// blocks), with the quiet zone the readers need. `None` for a URL too long for a QR code.
fn qr_code(url: &str) -> Option<String> {
    let code = qrcode::QrCode::new(url.as_bytes()).ok()?;
    Some(
        code.render::<qrcode::render::unicode::Dense1x2>()
            .quiet_zone(true)
            .build(),
    )
}

/// Serves `opts.root` until the process is stopped.
pub fn serve(opts: ServeOpts) -> Result<(), String> {
    if !opts.root.join("index.html").is_file() {
        return Err(format!(
            "{} has no index.html: build the site first (./dev build)",
            opts.root.display()
        ));
    }
    let root = Arc::new(opts.root.clone());
    let ips = lan_ips();
    let mut names = vec!["localhost".to_string(), "127.0.0.1".to_string()];
    names.extend(ips.iter().map(|ip| ip.to_string()));
    let cert_dir = opts.cert_dir.clone().unwrap_or_else(default_cert_dir);
    let (certificate, private_key) = certificate(&cert_dir, &names)?;
    let tls = tls_config(&certificate, &private_key)?;
    let http = TcpListener::bind(("127.0.0.1", opts.http_port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{}: {e}", opts.http_port))?;
    let https = TcpListener::bind(("0.0.0.0", opts.https_port))
        .map_err(|e| format!("cannot listen on 0.0.0.0:{}: {e}", opts.https_port))?;
    let http_port = http.local_addr().map_or(opts.http_port, |a| a.port());
    let https_port = https.local_addr().map_or(opts.https_port, |a| a.port());
    out!("Serving {}", opts.root.display());
    out!("  this machine:  http://localhost:{http_port}/");
    out!("                 https://localhost:{https_port}/");
    match ips.first() {
        Some(ip) => {
            let url = format!("https://{ip}:{https_port}/");
            for other in &ips[1..] {
                out!("  also:          https://{other}:{https_port}/");
            }
            out!("  phone (LAN):   {url}");
            out!("The certificate is self-signed: on the phone, accept the warning once.");
            if let Some(code) = qr_code(&url) {
                out!("{code}");
            }
        }
        None => out!("  no LAN address found: a phone cannot reach this machine"),
    }
    out!("Certificate: {}   Stop with Ctrl-C.", cert_dir.display());
    let a = spawn(http, root.clone(), None);
    let b = spawn(https, root, Some(tls));
    a.join()
        .map_err(|_| "the HTTP server stopped".to_string())?;
    b.join().map_err(|_| "the HTTPS server stopped".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mime_types() {
        assert_eq!(mime(Path::new("a/pdr_bg.wasm")), "application/wasm");
        assert_eq!(mime(Path::new("app.js")), "text/javascript; charset=utf-8");
        assert_eq!(mime(Path::new("index.HTML")), "text/html; charset=utf-8");
    }

    /// A connection in memory: the request in, the response out.
    struct Conn(std::io::Cursor<Vec<u8>>, Vec<u8>);
    impl Read for Conn {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            // A few bytes at a time, as a slow network delivers them.
            let n = buf.len().min(7);
            self.0.read(&mut buf[..n])
        }
    }
    impl Write for Conn {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.1.write(buf)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn ask(root: &Path, request: &[u8]) -> String {
        let mut c = Conn(std::io::Cursor::new(request.to_vec()), Vec::new());
        handle(root, &mut c).unwrap();
        String::from_utf8_lossy(&c.1).into_owned()
    }

    #[test]
    fn answers_one_request_and_closes() {
        let root = std::env::temp_dir().join(format!("pdr-serve-{}", std::process::id()));
        std::fs::create_dir_all(root.join("www")).unwrap();
        std::fs::write(root.join("index.html"), "<!doctype html>hi").unwrap();
        std::fs::write(root.join("www/app.js"), "let x = 1;").unwrap();
        let r = ask(
            &root,
            b"GET /www/app.js HTTP/1.1\r\nHost: x\r\nConnection: keep-alive\r\n\r\n",
        );
        assert!(r.starts_with("HTTP/1.1 200 OK\r\n"), "{r}");
        assert!(r.contains("Content-Type: text/javascript; charset=utf-8\r\n"));
        assert!(r.contains("Content-Length: 10\r\n") && r.contains("Connection: close\r\n"));
        assert!(r.ends_with("\r\n\r\nlet x = 1;"));
        let r = ask(&root, b"HEAD / HTTP/1.1\r\n\r\n");
        assert!(
            r.contains("Content-Length: 17\r\n") && r.ends_with("\r\n\r\n"),
            "{r}"
        );
        assert!(ask(&root, b"GET /../etc/passwd HTTP/1.1\r\n\r\n").starts_with("HTTP/1.1 404"));
        assert!(ask(&root, b"POST / HTTP/1.1\r\n\r\n").starts_with("HTTP/1.1 405"));
        let long = format!("GET / HTTP/1.1\r\nX: {}\r\n\r\n", "a".repeat(20_000));
        assert!(ask(&root, long.as_bytes()).starts_with("HTTP/1.1 431"));
        // A client that hangs up before the end of its request gets nothing.
        assert_eq!(ask(&root, b"GET / HT"), "");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn the_qr_code_is_square_half_blocks_with_its_quiet_zone() {
        // 26 bytes: a version-2 code, 25 modules and 4 of quiet zone on each side.
        let code = qr_code("https://192.168.1.20:8443/").unwrap();
        let lines: Vec<&str> = code.lines().collect();
        assert_eq!(lines.len(), 33_usize.div_ceil(2));
        for line in &lines {
            assert_eq!(line.chars().count(), 33, "{line:?}");
            assert!(line.chars().all(|c| " █▀▄".contains(c)), "{line:?}");
        }
        assert!(lines[0].trim().is_empty() && code.contains('█'));
        assert!(qr_code(&"x".repeat(8000)).is_none());
    }

    #[test]
    fn the_tls_configuration_reads_the_certificate_it_made() {
        let dir = std::env::temp_dir().join(format!("pdr-serve-cert-{}", std::process::id()));
        let names = ["localhost".to_string(), "127.0.0.1".to_string()];
        let (cert, key) = certificate(&dir, &names).unwrap();
        assert!(tls_config(&cert, &key).is_ok());
        // The same names: the same certificate, read back.
        assert_eq!(
            certificate(&dir, &names).unwrap(),
            (cert.clone(), key.clone())
        );
        assert!(tls_config(b"", &key)
            .unwrap_err()
            .contains("certificate: none"));
        assert!(tls_config(&cert, b"not a key")
            .unwrap_err()
            .starts_with("private key"));
        assert!(tls_config(&key, &cert).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn paths_stay_inside_the_root() {
        let root = Path::new("/srv/site");
        assert_eq!(
            resolve(root, "/www/app.js?v=1"),
            Some(PathBuf::from("/srv/site/www/app.js"))
        );
        assert_eq!(
            resolve(root, "/"),
            Some(PathBuf::from("/srv/site/index.html"))
        );
        assert_eq!(resolve(root, "/../etc/passwd"), None);
        assert_eq!(resolve(root, "/www/%2e%2e/%2e%2e/etc/passwd"), None);
        assert_eq!(
            resolve(root, "/a%20b.txt"),
            Some(PathBuf::from("/srv/site/a b.txt"))
        );
    }
}
