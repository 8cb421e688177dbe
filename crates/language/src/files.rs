//! Reading the files a user names: only regular files, never more than a
//! bound (SPEC 2.2 and §4: a FIFO, a device, a folder or a `/proc` entry is
//! refused at once, never waited on; `/dev/zero` cannot exhaust memory).
//! Every reader of user-named files — the scenario loader (the main file,
//! includes, maps), `fmt`, `import` and `bench merge` — goes through
//! [`read_regular_file`].

use std::fmt;
use std::io::Read;
use std::path::Path;

/// Why a file could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// It does not exist, or the system refused it.
    Io(std::io::Error),
    /// A folder, where a file was expected.
    Folder,
    /// A FIFO, a socket, a device, or an entry of the kernel's `/proc`,
    /// `/sys` or `/dev` file systems: its "size" means nothing, and reading
    /// it may block forever or never end.
    NotRegular(&'static str),
    /// Larger than the bound (bytes).
    TooLarge(u64),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Io(e) => write!(f, "{e}"),
            ReadError::Folder => write!(f, "it is a folder, not a file"),
            ReadError::NotRegular(what) => write!(f, "it is {what}, not a regular file"),
            ReadError::TooLarge(max) => write!(f, "it is larger than {}", human_bytes(*max)),
        }
    }
}

/// `16 MiB`, `512 KiB`, `100 bytes`.
pub fn human_bytes(n: u64) -> String {
    if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else if n >= 1 << 10 && n.is_multiple_of(1 << 10) {
        format!("{} KiB", n >> 10)
    } else {
        format!("{n} bytes")
    }
}

/// The kind of a file that is not regular, for messages.
fn kind_of(meta: &std::fs::Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_socket() {
            return Some("a socket");
        }
        if t.is_char_device() || t.is_block_device() {
            return Some("a device");
        }
    }
    Some("not a regular file")
}

/// Whether `path` (made absolute and free of symbolic links where it
/// exists) lies in a kernel file system whose entries look like regular
/// files but are not: their size is 0 and their content is the process's
/// (`/proc/self/environ`) or endless.
fn in_kernel_file_system(path: &Path) -> bool {
    let canonical = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    ["/proc", "/sys", "/dev"]
        .iter()
        .any(|k| canonical.starts_with(k))
}

/// Reads the regular file `path`, at most `max_bytes` of it.
///
/// Behaviour: the file's type is checked before it is opened (a FIFO is
/// never opened, so nothing waits for a writer), and again on the open file
/// (opened without blocking, in case it was swapped meanwhile); at most
/// `max_bytes + 1` bytes are read, so a file that grows while it is read
/// cannot exhaust memory either.
pub fn read_regular_file(path: &Path, max_bytes: u64) -> Result<Vec<u8>, ReadError> {
    let meta = std::fs::metadata(path).map_err(ReadError::Io)?;
    if meta.is_dir() {
        return Err(ReadError::Folder);
    }
    if let Some(kind) = kind_of(&meta) {
        return Err(ReadError::NotRegular(kind));
    }
    if in_kernel_file_system(path) {
        return Err(ReadError::NotRegular(
            "an entry of the kernel's /proc, /sys or /dev",
        ));
    }
    if meta.len() > max_bytes {
        return Err(ReadError::TooLarge(max_bytes));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // Should the path have become a FIFO since the check, opening it
        // must not wait for a writer.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(ReadError::Io)?;
    let meta = file.metadata().map_err(ReadError::Io)?;
    if let Some(kind) = kind_of(&meta) {
        return Err(ReadError::NotRegular(kind));
    }
    let mut bytes = Vec::with_capacity(meta.len().min(max_bytes) as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(ReadError::Io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(ReadError::TooLarge(max_bytes));
    }
    Ok(bytes)
}

/// Which file a path names on disk, symbolic links followed: on unix its
/// (device, inode), so that `x`, `./d/../x`, a symbolic link to `x` and a
/// hard link to it are all the same file; elsewhere its canonical path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileIdentity {
    #[cfg(unix)]
    id: (u64, u64),
    #[cfg(not(unix))]
    id: std::path::PathBuf,
}

/// The identity of the file `path` names, or `None` when there is no such
/// file (nor a folder): a path that does not exist yet is no file's.
pub fn file_identity(path: &Path) -> Option<FileIdentity> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let meta = std::fs::metadata(path).ok()?;
        Some(FileIdentity {
            id: (meta.dev(), meta.ino()),
        })
    }
    #[cfg(not(unix))]
    {
        Some(FileIdentity {
            id: path.canonicalize().ok()?,
        })
    }
}

/// Where the first invalid UTF-8 byte of `bytes` is: its 1-based line and
/// column (in characters of the valid text before it), or `None` when the
/// bytes are UTF-8.
pub fn invalid_utf8_at(bytes: &[u8]) -> Option<(usize, usize)> {
    let valid = match std::str::from_utf8(bytes) {
        Ok(_) => return None,
        Err(e) => e.valid_up_to(),
    };
    // The prefix is valid UTF-8 by construction.
    let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    Some((line, column))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("scen-files-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn reads_a_regular_file_within_the_bound() {
        let dir = temp("regular");
        let f = dir.join("a.txt");
        std::fs::write(&f, "hello").unwrap();
        assert_eq!(read_regular_file(&f, 5).unwrap(), b"hello");
        assert!(matches!(
            read_regular_file(&f, 4),
            Err(ReadError::TooLarge(4))
        ));
        assert!(matches!(
            read_regular_file(&dir, 100),
            Err(ReadError::Folder)
        ));
        assert!(matches!(
            read_regular_file(&dir.join("missing"), 100),
            Err(ReadError::Io(_))
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn refuses_devices_and_kernel_files_without_reading_them() {
        assert!(matches!(
            read_regular_file(Path::new("/dev/zero"), 100),
            Err(ReadError::NotRegular(_))
        ));
        assert!(matches!(
            read_regular_file(Path::new("/proc/self/environ"), 1 << 20),
            Err(ReadError::NotRegular(_))
        ));
    }

    #[cfg(unix)]
    #[test]
    fn refuses_a_fifo_without_waiting_for_a_writer() {
        let dir = temp("fifo");
        let fifo = dir.join("pipe.scen");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            eprintln!("skipped: mkfifo is not available");
            return;
        }
        assert!(matches!(
            read_regular_file(&fifo, 100),
            Err(ReadError::NotRegular("a FIFO (named pipe)"))
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_is_the_same_by_any_path_to_it() {
        let dir = temp("identity");
        let f = dir.join("a.scen");
        std::fs::write(&f, "robot p point\n").unwrap();
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let id = file_identity(&f).expect("an existing file has an identity");
        assert_eq!(file_identity(&dir.join("sub/../a.scen")), Some(id.clone()));
        assert_eq!(file_identity(&dir.join("./a.scen")), Some(id.clone()));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(&f, dir.join("link.scen")).unwrap();
            assert_eq!(file_identity(&dir.join("link.scen")), Some(id.clone()));
            std::fs::hard_link(&f, dir.join("hard.scen")).unwrap();
            assert_eq!(file_identity(&dir.join("hard.scen")), Some(id.clone()));
        }
        std::fs::write(dir.join("b.scen"), "robot p point\n").unwrap();
        assert_ne!(file_identity(&dir.join("b.scen")), Some(id));
        assert_eq!(file_identity(&dir.join("missing.scen")), None);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn locates_the_first_invalid_byte() {
        assert_eq!(invalid_utf8_at(b"abc"), None);
        assert_eq!(invalid_utf8_at(b"ab\ncd\xffe"), Some((2, 3)));
        assert_eq!(invalid_utf8_at("é\n\u{e9}".as_bytes()), None);
        assert_eq!(invalid_utf8_at(b"\xc3\xa9\xc3\xa9\xff"), Some((1, 3)));
        assert_eq!(invalid_utf8_at(b"\xc3"), Some((1, 1)));
    }

    #[test]
    fn byte_counts_read_well() {
        assert_eq!(human_bytes(16 << 20), "16 MiB");
        assert_eq!(human_bytes(512 << 10), "512 KiB");
        assert_eq!(human_bytes(100), "100 bytes");
    }
}
