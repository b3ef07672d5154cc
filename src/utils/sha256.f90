module superjoin_utils_sha256
  !! SHA-256 (FIPS 180-4) over a stream of bytes, for content keys and
  !! checksums (the condensation library). A sha256_t is fed by update (text,
  !! or the bytes of integer and real arrays) and closed by digest, which
  !! gives the 64 lower-case hexadecimal digits.
  !!
  !! Speed: arrays are hashed in place through a byte view of their storage
  !! (no copy), whole 64-byte blocks go straight to the compression, which
  !! works on 32-bit words in int32 (rotations and exclusive ors) with the
  !! modular sums formed in int64 and truncated, so that no signed
  !! arithmetic overflows.
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64
  use, intrinsic :: iso_c_binding, only: c_loc, c_f_pointer
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  integer, parameter :: BLOCK_BYTES = 64
    !! Bytes of one message block.
  integer(int32), parameter :: K(64) = [ &
       int(z'428a2f98', int32), int(z'71374491', int32), int(z'b5c0fbcf', int32), int(z'e9b5dba5', int32), &
       int(z'3956c25b', int32), int(z'59f111f1', int32), int(z'923f82a4', int32), int(z'ab1c5ed5', int32), &
       int(z'd807aa98', int32), int(z'12835b01', int32), int(z'243185be', int32), int(z'550c7dc3', int32), &
       int(z'72be5d74', int32), int(z'80deb1fe', int32), int(z'9bdc06a7', int32), int(z'c19bf174', int32), &
       int(z'e49b69c1', int32), int(z'efbe4786', int32), int(z'0fc19dc6', int32), int(z'240ca1cc', int32), &
       int(z'2de92c6f', int32), int(z'4a7484aa', int32), int(z'5cb0a9dc', int32), int(z'76f988da', int32), &
       int(z'983e5152', int32), int(z'a831c66d', int32), int(z'b00327c8', int32), int(z'bf597fc7', int32), &
       int(z'c6e00bf3', int32), int(z'd5a79147', int32), int(z'06ca6351', int32), int(z'14292967', int32), &
       int(z'27b70a85', int32), int(z'2e1b2138', int32), int(z'4d2c6dfc', int32), int(z'53380d13', int32), &
       int(z'650a7354', int32), int(z'766a0abb', int32), int(z'81c2c92e', int32), int(z'92722c85', int32), &
       int(z'a2bfe8a1', int32), int(z'a81a664b', int32), int(z'c24b8b70', int32), int(z'c76c51a3', int32), &
       int(z'd192e819', int32), int(z'd6990624', int32), int(z'f40e3585', int32), int(z'106aa070', int32), &
       int(z'19a4c116', int32), int(z'1e376c08', int32), int(z'2748774c', int32), int(z'34b0bcb5', int32), &
       int(z'391c0cb3', int32), int(z'4ed8aa4a', int32), int(z'5b9cca4f', int32), int(z'682e6ff3', int32), &
       int(z'748f82ee', int32), int(z'78a5636f', int32), int(z'84c87814', int32), int(z'8cc70208', int32), &
       int(z'90befffa', int32), int(z'a4506ceb', int32), int(z'bef9a3f7', int32), int(z'c67178f2', int32)]
    !! Round constants (fractional parts of the cube roots of the first 64 primes).
  integer(int32), parameter :: H0(8) = [ &
       int(z'6a09e667', int32), int(z'bb67ae85', int32), int(z'3c6ef372', int32), int(z'a54ff53a', int32), &
       int(z'510e527f', int32), int(z'9b05688c', int32), int(z'1f83d9ab', int32), int(z'5be0cd19', int32)]
    !! Initial hash value.
  logical, parameter :: LITTLE_ENDIAN = iachar(transfer(1_int32, 'a')) == 1
    !! Byte order of this machine (a word's first byte is its lowest).

  type, public :: sha256_t
    !! A hash in progress.
     integer(int32) :: h(8) = H0
     integer(int8) :: buf(BLOCK_BYTES) = 0_int8  !! bytes not yet compressed
     integer :: nbuf = 0
     integer(int64) :: length = 0               !! message bytes so far
  end type sha256_t

  interface update
    !! Feed bytes: text, or the storage of an integer or real array.
     module procedure update_text, update_int32, update_int64, update_real64, update_real64_2d
  end interface update

  public :: update, digest, sha256_hex

contains

  function sha256_hex(text) result(hex)
    !! The SHA-256 of text, 64 hexadecimal digits.
    character(*), intent(in) :: text
    character(len=64) :: hex
    type(sha256_t) :: s
    call update(s, text)
    hex = digest(s)
  end function sha256_hex

  subroutine update_text(s, text)
    !! Feed the bytes of text.
    type(sha256_t), intent(inout) :: s
    character(*), intent(in), target :: text
    integer(int8), pointer, contiguous :: b(:)
    if (len(text) == 0) return
    call c_f_pointer(c_loc(text), b, [len(text, kind=int64)])
    call update_bytes(s, b)
  end subroutine update_text

  subroutine update_int32(s, a)
    !! Feed the storage of a default-integer array.
    type(sha256_t), intent(inout) :: s
    integer(int32), intent(in), target, contiguous :: a(:)
    integer(int8), pointer, contiguous :: b(:)
    if (size(a) == 0) return
    call c_f_pointer(c_loc(a), b, [4*size(a, kind=int64)])
    call update_bytes(s, b)
  end subroutine update_int32

  subroutine update_int64(s, a)
    !! Feed the storage of an int64 array.
    type(sha256_t), intent(inout) :: s
    integer(int64), intent(in), target, contiguous :: a(:)
    integer(int8), pointer, contiguous :: b(:)
    if (size(a) == 0) return
    call c_f_pointer(c_loc(a), b, [8*size(a, kind=int64)])
    call update_bytes(s, b)
  end subroutine update_int64

  subroutine update_real64(s, a)
    !! Feed the storage of a real64 array.
    type(sha256_t), intent(inout) :: s
    real(wp), intent(in), target, contiguous :: a(:)
    integer(int8), pointer, contiguous :: b(:)
    if (size(a) == 0) return
    call c_f_pointer(c_loc(a), b, [8*size(a, kind=int64)])
    call update_bytes(s, b)
  end subroutine update_real64

  subroutine update_real64_2d(s, a)
    !! Feed the storage of a real64 matrix (column by column).
    type(sha256_t), intent(inout) :: s
    real(wp), intent(in), target, contiguous :: a(:, :)
    integer(int8), pointer, contiguous :: b(:)
    if (size(a) == 0) return
    call c_f_pointer(c_loc(a), b, [8*size(a, kind=int64)])
    call update_bytes(s, b)
  end subroutine update_real64_2d

  subroutine update_bytes(s, b)
    !! Feed the bytes b: the buffer topped up first, then whole blocks
    !! straight from b, the rest kept in the buffer.
    type(sha256_t), intent(inout) :: s
    integer(int8), intent(in), contiguous :: b(:)
    integer(int64) :: pos, n, take
    n = size(b, kind=int64)
    s%length = s%length + n
    pos = 1
    if (s%nbuf > 0) then
       take = min(int(BLOCK_BYTES - s%nbuf, int64), n)
       s%buf(s%nbuf + 1:s%nbuf + take) = b(1:take)
       s%nbuf = s%nbuf + int(take)
       pos = pos + take
       if (s%nbuf < BLOCK_BYTES) return
       call compress(s%h, s%buf)
       s%nbuf = 0
    end if
    do while (n - pos + 1 >= BLOCK_BYTES)
       call compress(s%h, b(pos:pos + BLOCK_BYTES - 1))
       pos = pos + BLOCK_BYTES
    end do
    s%nbuf = int(n - pos + 1)
    s%buf(1:s%nbuf) = b(pos:n)
  end subroutine update_bytes

  function digest(s) result(hex)
    !! Close the hash (padding and length) and give its 64 hexadecimal digits.
    type(sha256_t), intent(in) :: s
    character(len=64) :: hex
    type(sha256_t) :: t
    integer(int8) :: pad(BLOCK_BYTES + 8)
    integer(int64) :: bits
    integer :: i, nz, nib
    character(len=16), parameter :: DIGITS = '0123456789abcdef'
    t = s
    bits = t%length*8
    nz = modulo(55 - t%nbuf, BLOCK_BYTES)   ! zeros so that the length ends a block
    pad = 0_int8
    pad(1) = -huge(0_int8) - 1_int8         ! the byte 0x80
    do i = 1, 8
       pad(1 + nz + i) = int(ibits(bits, 8*(8 - i), 8), int8)
    end do
    call update_bytes(t, pad(1:nz + 9))
    do i = 1, 64
       nib = iand(shiftr(t%h(shiftr(i - 1, 3) + 1), 4*(7 - mod(i - 1, 8))), 15) + 1
       hex(i:i) = DIGITS(nib:nib)
    end do
  end function digest

  pure integer(int32) function rotr(x, n)
    !! Rotate the 32-bit word x right by n bits.
    integer(int32), intent(in) :: x
    integer, intent(in) :: n
    rotr = ior(shiftr(x, n), shiftl(x, 32 - n))
  end function rotr

  pure integer(int32) function bswap(x)
    !! x with its four bytes in the other order (a big-endian word loaded on a
    !! little-endian machine).
    integer(int32), intent(in) :: x
    bswap = ior(ior(shiftl(x, 24), iand(shiftl(x, 8), int(z'00FF0000', int32))), &
         ior(iand(shiftr(x, 8), int(z'0000FF00', int32)), shiftr(x, 24)))
  end function bswap

  pure subroutine compress(h, blk)
    !! One block of the compression function.
    integer(int32), intent(inout) :: h(8)
    integer(int8), intent(in) :: blk(BLOCK_BYTES)
    integer(int32) :: w(64), a, b, c, d, e, f, g, hh, s0, s1, t1, t2
    integer :: i
    w(1:16) = transfer(blk, w, 16)
    if (LITTLE_ENDIAN) then
       do i = 1, 16
          w(i) = bswap(w(i))
       end do
    end if
    do i = 17, 64   ! sums modulo 2**32: formed in int64, truncated
       s0 = ieor(ieor(rotr(w(i - 15), 7), rotr(w(i - 15), 18)), shiftr(w(i - 15), 3))
       s1 = ieor(ieor(rotr(w(i - 2), 17), rotr(w(i - 2), 19)), shiftr(w(i - 2), 10))
       w(i) = int(int(w(i - 16), int64) + s0 + w(i - 7) + s1, int32)
    end do
    a = h(1); b = h(2); c = h(3); d = h(4); e = h(5); f = h(6); g = h(7); hh = h(8)
    do i = 1, 64
       s1 = ieor(ieor(rotr(e, 6), rotr(e, 11)), rotr(e, 25))
       t1 = int(int(hh, int64) + s1 + ieor(g, iand(e, ieor(f, g))) + K(i) + w(i), int32)   ! ch(e, f, g)
       s0 = ieor(ieor(rotr(a, 2), rotr(a, 13)), rotr(a, 22))
       t2 = int(int(s0, int64) + ior(iand(a, ior(b, c)), iand(b, c)), int32)               ! maj(a, b, c)
       hh = g; g = f; f = e
       e = int(int(d, int64) + t1, int32)
       d = c; c = b; b = a
       a = int(int(t1, int64) + t2, int32)
    end do
    h(1) = add(h(1), a); h(2) = add(h(2), b); h(3) = add(h(3), c); h(4) = add(h(4), d)
    h(5) = add(h(5), e); h(6) = add(h(6), f); h(7) = add(h(7), g); h(8) = add(h(8), hh)
  end subroutine compress

  pure integer(int32) function add(x, y)
    !! x + y modulo 2**32.
    integer(int32), intent(in) :: x, y
    add = int(int(x, int64) + y, int32)
  end function add
end module superjoin_utils_sha256
