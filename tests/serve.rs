//! `pdr serve` as a phone meets it: the binary started on free ports, a real TLS handshake with
//! a client that trusts only the certificate the server made (for `localhost` and `127.0.0.1`),
//! a GET over it and over plain HTTP, a client that does not trust it refused, garbage on the
//! TLS port not stopping the server, and the QR code of the LAN address printed. The request
//! handling itself is tested in `src/bin/pdr/serve.rs`.
#![cfg(not(target_arch = "wasm32"))]

use rustls::pki_types::pem::PemObject;
use rustls::pki_types::{CertificateDer, ServerName};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::Arc;

/// The running server, stopped when dropped (also when a check fails).
struct Server {
    child: Child,
    /// Standard output up to the certificate line: the addresses and the QR code.
    banner: String,
    http: u16,
    https: u16,
    cert_dir: PathBuf,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A fresh folder for one test's site and certificate.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pdr-serve-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("site/www")).unwrap();
    std::fs::write(dir.join("site/index.html"), "<!doctype html>hello").unwrap();
    std::fs::write(dir.join("site/www/app.js"), "let x = 1;").unwrap();
    dir
}

/// The port of the first `prefix…:PORT/` address in the banner.
fn port_after(banner: &str, prefix: &str) -> u16 {
    let rest = &banner[banner.find(prefix).expect(prefix) + prefix.len()..];
    rest[..rest.find('/').unwrap()].parse().unwrap()
}

/// Starts `pdr serve` on ports the system picks, over the site of [`scratch`] `dir`, with the
/// certificate in `dir/cert`.
fn start(dir: &Path) -> Server {
    let (root, cert_dir) = (dir.join("site"), dir.join("cert"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_pdr"))
        .args(["serve", "--http-port", "0", "--https-port", "0", "--root"])
        .arg(&root)
        .arg("--cert-dir")
        .arg(&cert_dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut banner = String::new();
    let mut lines = BufReader::new(child.stdout.take().unwrap());
    while !banner.contains("Certificate:") {
        let mut line = String::new();
        if lines.read_line(&mut line).unwrap() == 0 {
            panic!("pdr serve ended early:\n{banner}");
        }
        banner += &line;
    }
    let http = port_after(&banner, "http://localhost:");
    let https = port_after(&banner, "https://localhost:");
    Server {
        child,
        banner,
        http,
        https,
        cert_dir,
    }
}

/// A TLS client trusting the certificates of `roots` only, with ring as the provider.
fn client(roots: rustls::RootCertStore) -> Arc<rustls::ClientConfig> {
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    let config = rustls::ClientConfig::builder_with_provider(provider)
        .with_safe_default_protocol_versions()
        .unwrap()
        .with_root_certificates(roots)
        .with_no_client_auth();
    Arc::new(config)
}

/// The server's own certificate as the only trusted root.
fn trusting(cert_dir: &Path) -> Arc<rustls::ClientConfig> {
    let mut roots = rustls::RootCertStore::empty();
    for cert in CertificateDer::pem_file_iter(cert_dir.join("cert.pem")).unwrap() {
        roots.add(cert.unwrap()).unwrap();
    }
    assert_eq!(roots.len(), 1);
    client(roots)
}

/// GET `path` over TLS to `name` at 127.0.0.1:`port`: the response, or the error.
fn get_tls(
    config: Arc<rustls::ClientConfig>,
    name: &str,
    port: u16,
    path: &str,
) -> std::io::Result<String> {
    let name = ServerName::try_from(name.to_string()).unwrap();
    let conn = rustls::ClientConnection::new(config, name).unwrap();
    let sock = TcpStream::connect(("127.0.0.1", port))?;
    let mut tls = rustls::StreamOwned::new(conn, sock);
    write!(tls, "GET {path} HTTP/1.1\r\nHost: localhost\r\n\r\n")?;
    let mut out = Vec::new();
    tls.read_to_end(&mut out)?;
    assert_eq!(
        tls.conn.protocol_version(),
        Some(rustls::ProtocolVersion::TLSv1_3)
    );
    Ok(String::from_utf8_lossy(&out).into_owned())
}

#[test]
fn https_with_the_self_signed_certificate_and_the_qr_code() {
    let dir = scratch("tls");
    let s = start(&dir);
    for name in ["localhost", "127.0.0.1"] {
        let r = get_tls(trusting(&s.cert_dir), name, s.https, "/www/app.js").unwrap();
        assert!(r.starts_with("HTTP/1.1 200 OK\r\n"), "{name}: {r}");
        assert!(r.contains("Content-Type: text/javascript; charset=utf-8\r\n"));
        assert!(r.ends_with("\r\n\r\nlet x = 1;"), "{r}");
    }
    let r = get_tls(trusting(&s.cert_dir), "localhost", s.https, "/nothing").unwrap();
    assert!(r.starts_with("HTTP/1.1 404"), "{r}");

    // A client that does not trust the certificate is refused in the handshake.
    let e = get_tls(
        client(rustls::RootCertStore::empty()),
        "localhost",
        s.https,
        "/",
    )
    .unwrap_err();
    assert!(e.to_string().contains("invalid peer certificate"), "{e}");

    // Garbage, and a client that hangs up mid-handshake, do not stop the server.
    let mut raw = TcpStream::connect(("127.0.0.1", s.https)).unwrap();
    raw.write_all(b"GET / HTTP/1.1\r\n\r\n").unwrap();
    let mut answer = Vec::new();
    let _ = raw.read_to_end(&mut answer);
    drop(TcpStream::connect(("127.0.0.1", s.https)).unwrap());
    let r = get_tls(trusting(&s.cert_dir), "localhost", s.https, "/").unwrap();
    assert!(r.ends_with("\r\n\r\n<!doctype html>hello"), "{r}");

    // Plain HTTP on localhost.
    let mut plain = TcpStream::connect(("127.0.0.1", s.http)).unwrap();
    plain.write_all(b"GET / HTTP/1.1\r\n\r\n").unwrap();
    let mut r = String::new();
    plain.read_to_string(&mut r).unwrap();
    assert!(
        r.starts_with("HTTP/1.1 200 OK\r\n") && r.ends_with("hello"),
        "{r}"
    );

    // The phone's address with its QR code (half blocks), when the machine has a LAN address.
    if s.banner.contains("phone (LAN):   https://") {
        let blocks = s.banner.lines().filter(|l| l.contains('█')).count();
        assert!(blocks >= 10, "{}", s.banner);
    } else {
        assert!(s.banner.contains("no LAN address found"), "{}", s.banner);
    }
    drop(s);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_certificate_is_kept_and_reused() {
    let dir = scratch("keep");
    let first = start(&dir);
    let pem = std::fs::read(first.cert_dir.join("cert.pem")).unwrap();
    let trust = trusting(&first.cert_dir);
    drop(first);
    let second = start(&dir);
    assert_eq!(
        std::fs::read(second.cert_dir.join("cert.pem")).unwrap(),
        pem
    );
    let r = get_tls(trust, "localhost", second.https, "/").unwrap();
    assert!(r.ends_with("hello"), "{r}");
    drop(second);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_folder_without_a_site_is_a_clear_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_pdr"))
        .args(["serve", "--http-port", "0", "--https-port", "0", "--root"])
        .arg(std::env::temp_dir().join("pdr-serve-test-no-such-site"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("has no index.html: build the site first"), "{e}");
}
